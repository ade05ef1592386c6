use newtons_cradle::config::Config;
use newtons_cradle::scene::CradleWorld;
use newtons_cradle::trace::{
    Prepared, Shape, camera::CameraRays, motion::Motion, shade, tiles::Tiles,
};

#[inline(never)]
fn class_floor(p: &Prepared, t: &Tiles, px: &[(u32, u32)], cam: &CameraRays, bound: f32) -> f32 {
    let mut s = 0.0;
    for &(x, y) in px {
        let r = cam.ray(x as f32 + 0.5, y as f32 + 0.5);
        let mut m = Motion::new(None);
        s += shade::trace_primary(p, &r, (t, x, y), bound, &mut m).x;
    }
    s
}
#[inline(never)]
fn class_cyl(p: &Prepared, t: &Tiles, px: &[(u32, u32)], cam: &CameraRays, bound: f32) -> f32 {
    class_floor(p, t, px, cam, bound) + 0.0
}
#[inline(never)]
fn class_sphere(p: &Prepared, t: &Tiles, px: &[(u32, u32)], cam: &CameraRays, bound: f32) -> f32 {
    class_floor(p, t, px, cam, bound) * 1.0
}

#[test]
fn probe() {
    let mut config = Config::default();
    config.render.width = 600;
    config.render.height = 300;
    let mut world = CradleWorld::new(&config);
    world.show_at(0.37);
    let s = world.scene().clone();
    let p = Prepared::new(&s).with_shadow_culling(true).with_bvh(true);
    let bound = shade::radiance_bound(&p);
    let cam = CameraRays::new(&s.camera, 600, 300);
    let tiles = Tiles::new(&p, &cam, 600, 300);
    let (mut f, mut c, mut sp) = (vec![], vec![], vec![]);
    for y in 0..300 {
        for x in (0..600).step_by(8) {
            if tiles.only_plane(&p, x, y, 8).is_some() {
                continue;
            }
            for x in x..x + 8 {
                let ray = cam.ray(x as f32 + 0.5, y as f32 + 0.5);
                match p
                    .closest(&ray, f32::INFINITY)
                    .map(|h| &s.objects[h.object].shape)
                {
                    Some(Shape::Sphere { .. }) => sp.push((x, y)),
                    Some(Shape::Cylinder { .. }) => c.push((x, y)),
                    _ => f.push((x, y)),
                }
            }
        }
    }
    let a = class_floor(&p, &tiles, &f, &cam, bound);
    let b = class_cyl(&p, &tiles, &c, &cam, bound);
    let d = class_sphere(&p, &tiles, &sp, &cam, bound);
    println!(
        "floor {} cyl {} sphere {} ({a} {b} {d})",
        f.len(),
        c.len(),
        sp.len()
    );
}
