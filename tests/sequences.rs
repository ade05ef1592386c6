//! `render --frames N --first K`: a long sequence split across processes gives
//! the same files, byte for byte, as one process rendering it all.

mod common;

use common::{run, stderr, temp_dir};

#[test]
fn a_sequence_split_in_two_equals_it_rendered_whole() {
    let dir = temp_dir("split");
    let (whole, split) = (dir.join("whole"), dir.join("split"));
    let render = |out: &std::path::Path, extra: &[&str]| {
        let mut args = vec![
            "render", "--fps", "20", "--time", "0.2", "--width", "48", "--height", "24", "--out",
        ];
        let out = format!("{}/", out.display());
        args.push(&out);
        args.extend_from_slice(extra);
        let o = run(&args);
        assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    };
    render(&whole, &["--frames", "6"]);
    render(&split, &["--frames", "3"]);
    render(&split, &["--frames", "3", "--first", "3"]);
    for n in 0..6 {
        let name = format!("frame_{n:04}.png");
        let (a, b) = (
            std::fs::read(whole.join(&name)).expect("whole"),
            std::fs::read(split.join(&name)).expect("split"),
        );
        assert!(a == b, "{name} differs");
    }
    // --first only makes sense for a PNG sequence.
    let o = run(&["render", "--gif", "x.gif", "--first", "2"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("--first"), "{}", stderr(&o));
    std::fs::remove_dir_all(&dir).ok();
}
