//! Anti-aliasing's extra samples over the lanes: eight camera rays through any
//! points of the picture (an edge pixel's other samples, several pixels' at a
//! time), each traced by the bounces from the eye as the scalar
//! `trace_primary` traces it (the tile's lists only skip what cannot be met).

use super::bounce::bounce_copy;
use super::rays::Bounce8;
use super::{LANES, Packet, V8};
use crate::simd::{Build, Portable};
use glam::Vec3;

impl Packet<'_, '_> {
    /// The radiance of the camera rays through the picture points `at` (at
    /// most [`LANES`]; lane `i` is `at[i]`), as `CameraRays::ray` makes them.
    /// In a tracked frame each lane's cells and segments are noted (`marks`,
    /// [`Self::lane_segs`]), those of earlier calls dropped.
    pub(crate) fn camera_samples(&self, at: &[(f32, f32)]) -> [Vec3; LANES] {
        assert!(at.len() <= LANES, "at most {LANES} samples at a time");
        self.fresh();
        let mut first = Bounce8 {
            origin: V8::ZERO,
            d: V8::ZERO,
            depth: 0,
            weight: [1.0; LANES],
            free: 0,
            from: [-1.0; LANES],
        };
        let mut live = 0u8;
        for (i, &(x, y)) in at.iter().enumerate() {
            let ray = self.cam.ray(x, y);
            first.origin.set(i, ray.origin);
            first.d.set(i, ray.dir);
            live |= 1 << i;
        }
        let c = self.trace_eye(&first, live);
        std::array::from_fn(|i| Vec3::new(c.x[i], c.y[i], c.z[i]))
    }

    /// The bounces of `first` in the lanes of `live`, in the best lane build.
    fn trace_eye(&self, first: &Bounce8, live: u8) -> V8 {
        match Build::detect() {
            Build::Portable => bounce_copy(Portable, self, first, live, None),
            #[cfg(target_arch = "x86_64")]
            Build::Avx2(s) => bounce_copy(s, self, first, live, None),
        }
    }
}
