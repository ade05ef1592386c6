//! The session's tracer: the incremental renderer, called in line, or, while the
//! swing runs in the window, one frame behind on the render pool: the window
//! shows frame N while frame N + 1 traces, so presenting it (the copy to the GPU,
//! the compositor's work) and tracing share the CPUs instead of taking turns.
//! While frame N + 1 prepares, frame N's picture is lent out, so the window
//! copies it to its framebuffer then ([`Tracer::give_back`]).
//! Window-free.

use crate::trace::{Change, Changes, Image, Incremental, Lent, Scene};
use std::sync::mpsc;
use std::time::Instant;

/// What a frame traced on the pool sends back: the renderer, and how long the
/// trace took (ms).
type Done = (Incremental, f64);

/// The renderer, at home or away tracing a frame on the pool.
#[derive(Debug)]
pub struct Tracer {
    /// The renderer while at home (`None` while it traces on the pool).
    home: Option<Incremental>,
    /// The frame tracing on the pool.
    away: Option<mpsc::Receiver<Done>>,
    /// Running frames trace on the pool, one frame behind ([`Self::frame`]).
    pipelined: bool,
    /// A frame waits for [`Self::launch_due`].
    due: bool,
    /// What changed since the renderer's last frame, not traced yet.
    pending: Change,
    /// The last picture, lent out while the renderer prepares the next frame
    /// on the pool, and where to give it back.
    lent: Option<(Lent, mpsc::SyncSender<Lent>)>,
}

impl Default for Tracer {
    fn default() -> Self {
        Self {
            home: Some(Incremental::new()),
            away: None,
            pipelined: false,
            due: false,
            pending: Change::none(),
            lent: None,
        }
    }
}

impl Tracer {
    /// Waits for the frame tracing on the pool, if one is, and takes the renderer
    /// back: how long that frame took to trace (ms).
    pub fn join(&mut self) -> Option<f64> {
        self.give_back();
        let away = self.away.take()?;
        if let Ok((renderer, ms)) = away.recv() {
            self.home = Some(renderer);
            Some(ms)
        } else {
            // The trace died with the renderer (rayon aborts on a panic, so this
            // is defensive): start afresh, the next frame in full.
            tracing::error!("the tracer stopped; tracing the next frame afresh");
            self.home = Some(Incremental::new());
            None
        }
    }

    /// Running frames from now on trace on the pool, one frame behind.
    pub fn pipeline(&mut self) {
        self.pipelined = true;
    }

    /// A frame of `scene`, `change` saying what changed since the frame
    /// before (the world's `take_change`): pipelined and `running`, left for
    /// [`Self::launch_due`] (`None`); else traced now, with how long it took
    /// (ms).
    pub fn frame(
        &mut self,
        pool: &rayon::ThreadPool,
        (scene, change): (&Scene, Change),
        running: bool,
    ) -> Option<f64> {
        if self.pipelined && running {
            self.pending.merge(change);
            self.due = true;
            None
        } else {
            Some(self.trace(pool, scene, change))
        }
    }

    /// Starts the frame [`Self::frame`] left, if it left one, tracing `scene`.
    pub fn launch_due(&mut self, pool: &rayon::ThreadPool, scene: &Scene) {
        if std::mem::take(&mut self.due) {
            self.launch(pool, scene.clone(), Change::none());
        }
    }

    /// What changed since the renderer's last frame: `change`, after what
    /// frames not traced left.
    fn since_last(&mut self, change: Change) -> Change {
        let mut all = std::mem::replace(&mut self.pending, Change::none());
        all.merge(change);
        all
    }

    /// Traces `scene` on `pool` now (after the frame on the pool, if any),
    /// `change` saying what changed since the frame before: how long it took
    /// (ms).
    pub fn trace(&mut self, pool: &rayon::ThreadPool, scene: &Scene, change: Change) -> f64 {
        self.join();
        let change = self.since_last(change);
        let renderer = self.home.get_or_insert_with(Incremental::new);
        let start = Instant::now();
        pool.install(|| {
            renderer.render_changed(scene, &change);
        });
        start.elapsed().as_secs_f64() * 1e3
    }

    /// Starts tracing `scene` on `pool` and returns at once, `change` saying
    /// what changed since the frame before: [`Self::join`] takes the frame
    /// back.
    pub fn launch(&mut self, pool: &rayon::ThreadPool, scene: Scene, change: Change) {
        self.join();
        let change = self.since_last(change);
        let mut renderer = self.home.take().unwrap_or_default();
        let (done, away) = mpsc::sync_channel(1);
        // The picture stays here, readable, while the frame prepares; without
        // one the sender goes at once and the frame does not wait.
        let (give, back) = mpsc::sync_channel(1);
        self.lent = renderer.lend().map(|lent| (lent, give));
        pool.spawn(move || {
            let start = Instant::now();
            renderer.render_lent(&scene, &change, || back.recv().ok());
            // Nobody waits when the session has ended meanwhile: nothing to do.
            let _ = done.send((renderer, start.elapsed().as_secs_f64() * 1e3));
        });
        self.away = Some(away);
    }

    /// Gives the picture lent out at [`Self::launch`] back to the frame on the
    /// pool, which waits for it to trace; [`Self::join`] does so first.
    pub fn give_back(&mut self) {
        if let Some((lent, give)) = self.lent.take() {
            // A frame that needs no picture (one ray per block) has not waited
            // for it, and may have ended: then the picture goes.
            let _ = give.send(lent);
        }
    }

    /// The last frame traced and taken back, or lent out while the next one
    /// prepares (`None` before the first, and while a frame traces on the
    /// pool, once the picture is given back).
    #[must_use]
    pub fn image(&self) -> Option<&Image> {
        match &self.home {
            Some(home) => home.image(),
            None => self.lent.as_ref().map(|(l, _)| l.image()),
        }
    }

    /// Which pixels the frame of [`Self::image`] changed (`None` when it is
    /// `None`).
    #[must_use]
    pub fn changes(&self) -> Option<Changes<'_>> {
        match &self.home {
            Some(home) => home.changes(),
            None => self.lent.as_ref().map(|(l, _)| l.changes()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::Tracer;
    use crate::config::Config;
    use crate::scene::CradleWorld;
    use crate::trace::Incremental;

    /// A small cradle swinging, and a pool of two to trace it on.
    fn swinging() -> (CradleWorld, rayon::ThreadPool) {
        let mut config = Config::default();
        (config.render.width, config.render.height) = (64, 32);
        let mut world = CradleWorld::new(&config);
        world.set_running(true);
        (world, crate::trace::pool(2).expect("a pool"))
    }

    #[test]
    fn a_frame_launched_on_the_pool_comes_back_as_the_same_picture_traced_in_line() {
        let (mut world, pool) = swinging();
        let (mut inline, mut away) = (Tracer::default(), Tracer::default());
        let mut before: Option<Vec<u8>> = None;
        for k in 0..6 {
            world.frame(0.05);
            let change = world.take_change();
            inline.trace(&pool, world.scene(), change.clone());
            away.launch(&pool, world.scene().clone(), change);
            // While the frame prepares, the picture before it is lent out.
            let lent = away.image().map(|i| i.rgba.clone());
            assert!(lent == before, "frame {k}: the picture before, lent out");
            assert_eq!(
                away.changes().map(|c| c.since.is_some()),
                before.as_ref().map(|_| k > 1),
                "frame {k}: its changes with it (the first frame is full)"
            );
            // Given back at once, or by the join itself.
            if k % 2 == 0 {
                away.give_back();
                assert!(away.image().is_none(), "the renderer is away");
            }
            assert!(away.join().is_some_and(|ms| ms >= 0.0));
            assert!(away.join().is_none(), "nothing left to take back");
            let (a, b) = (inline.image().expect("traced"), away.image().expect("back"));
            assert_eq!((a.width, a.height), (64, 32));
            assert!(
                a.rgba == b.rgba,
                "the same bytes, traced on the pool or in line"
            );
            before = Some(b.rgba.clone());
        }
    }

    #[test]
    fn a_frame_whose_picture_is_not_given_back_is_traced_in_full_to_the_same_bytes() {
        let (mut world, pool) = swinging();
        let (mut inline, mut lending) = (Incremental::new(), Incremental::new());
        // The first frame has nothing to lend; the second gets its picture
        // back; the third's is dropped.
        for (k, full) in [(0, true), (1, false), (2, true)] {
            world.frame(0.05);
            let change = world.take_change();
            let scene = world.scene();
            pool.install(|| {
                inline.render_changed(scene, &change);
                let lent = lending.lend();
                assert_eq!(lent.is_some(), k > 0, "frame {k}: a picture to lend");
                let back = (k == 1).then_some(lent).flatten();
                lending.render_lent(scene, &change, || back);
            });
            assert_eq!(lending.last_was_full(), full, "frame {k}");
            let (a, b) = (
                inline.image().expect("traced"),
                lending.image().expect("traced"),
            );
            assert!(a.rgba == b.rgba, "frame {k}: the bytes traced in line");
        }
    }
}
