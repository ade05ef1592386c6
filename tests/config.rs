//! The config asset: defaults, located errors for every kind of bad input.

use newtons_cradle::config::{Config, ConfigError, DEFAULT_ASSET, load_file, parse};

#[test]
fn the_shipped_asset_is_exactly_the_documented_defaults() {
    let parsed = parse(DEFAULT_ASSET, "assets/cradle.ron").expect("the default asset is valid");
    assert_eq!(parsed, Config::default());
}

#[test]
fn missing_keys_take_their_defaults() {
    let c = parse("(cradle: (balls: 9))", "t.ron").expect("valid");
    assert_eq!(c.cradle.balls, 9);
    assert_eq!(c.cradle.radius, Config::default().cradle.radius);
    assert_eq!(c.lights, Config::default().lights);
    // Options may be written bare or as Some(..).
    let c = parse("(materials: (ball: (specular: 50.0)))", "t.ron").expect("valid");
    assert_eq!(c.materials.ball.specular, Some(50.0));
}

/// Each bad field, written on line 3, gives its path, its line and what is allowed.
#[test]
fn every_out_of_range_field_is_located() {
    let cases = [
        ("cradle", "balls: 0", "cradle.balls", "1..=200"),
        ("cradle", "balls: 201", "cradle.balls", "1..=200"),
        ("cradle", "radius: -0.1", "cradle.radius", "1e-4..=10"),
        ("cradle", "radius: 1e400", "cradle.radius", "finite"),
        ("cradle", "density: 0.0", "cradle.density", "1..=1e5"),
        ("cradle", "length: 0.01", "cradle.length", "> radius"),
        ("cradle", "gap: -0.01", "cradle.gap", "0..=10"),
        (
            "cradle",
            "pivot_height: 0.1",
            "cradle.pivot_height",
            "clear the floor",
        ),
        (
            "cradle",
            "rail_spread: 0.001",
            "cradle.rail_spread",
            "> radius",
        ),
        ("cradle", "gravity: -9.81", "cradle.gravity", "1e-3..=1e4"),
        (
            "cradle",
            "string_radius: 0.5",
            "cradle.string_radius",
            "< radius",
        ),
        ("cradle", "frame_radius: 0.0", "cradle.frame_radius", "> 0"),
        ("start", "lift: 6", "start.lift", "0..=5"),
        (
            "start",
            "angle_deg: 180.0",
            "start.angle_deg",
            "0..=179.999",
        ),
        ("start", "angle_deg: -5.0", "start.angle_deg", "0..=179.999"),
        (
            "contact",
            "restitution: 1.5",
            "contact.restitution",
            "0..=1",
        ),
        (
            "contact",
            "youngs_modulus: 0.0",
            "contact.youngs_modulus",
            "1e5..=1e13",
        ),
        (
            "contact",
            "poisson_ratio: 0.5",
            "contact.poisson_ratio",
            "< 0.5",
        ),
        ("physics", "dt: 0.0", "physics.dt", "1e-7..=0.1"),
        ("render", "width: 8", "render.width", "16..=8192"),
        ("render", "height: 9000", "render.height", "16..=8192"),
        ("render", "max_depth: 17", "render.max_depth", "0..=16"),
        ("render", "samples: 0", "render.samples", "1..=64"),
        ("render", "threads: 1000", "render.threads", "0..=256"),
        (
            "render",
            "background: (2.0, 0.0, 0.0)",
            "render.background",
            "0..=1",
        ),
        ("camera", "fov_deg: 0.5", "camera.fov_deg", "1..=170"),
        ("sound", "volume: 1.5", "sound.volume", "0..=1"),
        ("sound", "volume: -0.1", "sound.volume", "0..=1"),
    ];
    // Looking at the eye itself: derived from the defaults, so it follows them.
    let eye = Config::default().camera.position;
    let look_at_eye = format!("look_at: ({:?}, {:?}, {:?})", eye[0], eye[1], eye[2]);
    let last = [(
        "camera",
        look_at_eye.as_str(),
        "camera.look_at",
        "from camera.position",
    )];
    for &(section, field, path, allowed) in cases.iter().chain(&last) {
        let src = format!("(\n  {section}: (\n    {field},\n  ),\n)\n");
        let err = parse(&src, "bad.ron").expect_err(field);
        let msg = err.to_string();
        assert!(matches!(err, ConfigError::Invalid { .. }), "{field}: {msg}");
        assert!(msg.starts_with("bad.ron:3:5: "), "{field}: {msg}");
        assert!(
            msg.contains(path) && msg.contains(allowed),
            "{field}: {msg}"
        );
    }
}

#[test]
fn bad_lights_and_materials_are_located() {
    let src = "(\n lights: [\n  Ambient(color: (1, 1, 1), intensity: 0.1),\n  Point(position: (0, 1, 1), color: (1, 1, 1), intensity: -1.0),\n ],\n materials: (\n  floor: (reflective: 2.0),\n ),\n)";
    let msg = parse(src, "l.ron").expect_err("invalid").to_string();
    assert!(msg.contains("l.ron:4:48: `lights[1].intensity`"), "{msg}");
    assert!(
        msg.contains("l.ron:7:11: `materials.floor.reflective`"),
        "{msg}"
    );
}

#[test]
fn syntax_errors_name_line_column_and_what_is_allowed() {
    let err =
        parse("(\n  cradle: (\n    ballz: 3,\n  ),\n)", "typo.ron").expect_err("unknown field");
    let msg = err.to_string();
    assert!(msg.starts_with("typo.ron:3:"), "{msg}");
    assert!(
        msg.contains("ballz") && msg.contains("balls"),
        "names the field and the allowed ones: {msg}"
    );

    let msg = parse("(cradle: (balls: 1e400))", "big.ron")
        .expect_err("not an integer")
        .to_string();
    assert!(msg.starts_with("big.ron:1:"), "{msg}");

    let msg = parse("", "empty.ron").expect_err("empty").to_string();
    assert!(msg.starts_with("empty.ron:1:"), "{msg}");

    let msg = parse("(contact: (model: springy))", "m.ron")
        .expect_err("bad variant")
        .to_string();
    assert!(msg.contains("m.ron:1:") && msg.contains("ideal"), "{msg}");
}

#[test]
fn unreadable_and_binary_files_are_errors_not_panics() {
    let dir = std::env::temp_dir().join(format!("nc-config-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let missing = dir.join("missing.ron");
    assert!(matches!(load_file(&missing), Err(ConfigError::Read { .. })));
    let binary = dir.join("garbage.ron");
    std::fs::write(&binary, [0xff, 0xfe, 0x00, 0x9f, 0x80, 0x01]).expect("write");
    assert!(matches!(
        load_file(&binary),
        Err(ConfigError::NotText { .. })
    ));
    let text_garbage = dir.join("noise.ron");
    std::fs::write(&text_garbage, "\u{1}\u{2}@@@ ((( ]]]").expect("write");
    assert!(matches!(
        load_file(&text_garbage),
        Err(ConfigError::Syntax { .. })
    ));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn hertz_contact_is_accepted_and_elastic_only() {
    let ok = parse("(contact: (model: hertz))", "hertz.ron").expect("hertz is valid");
    let k = ok.cradle_params().hertz.expect("hertz stiffness set");
    assert!(k > 0.0 && k.is_finite());
    assert!(Config::default().cradle_params().hertz.is_none());
    let src = "(\n  contact: (\n    model: hertz,\n    restitution: 0.5,\n  ),\n)\n";
    let msg = parse(src, "bad.ron")
        .expect_err("inelastic hertz")
        .to_string();
    assert!(msg.starts_with("bad.ron:4:5: "), "{msg}");
    assert!(
        msg.contains("contact.restitution") && msg.contains("hertz"),
        "{msg}"
    );
}

#[test]
fn text_with_wide_characters_before_a_colon_is_an_error_not_a_panic() {
    // Found by the fuzz test: naming the key before an error cut the text inside
    // a character wider than one byte.
    for text in [
        "/*\u{fffc}:/a",
        "(cradle: (b\u{e9}\u{2192}: x))",
        "(\u{1f600}: 1)",
    ] {
        assert!(parse(text, "wide.ron").is_err(), "{text:?}");
    }
}
