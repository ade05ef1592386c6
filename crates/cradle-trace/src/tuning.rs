//! The tracer's tuning constants, in one place: each trades work between two
//! ways to the same picture (every choice renders the same bytes, tested), and
//! was chosen by callgrind's instruction counts on the benchmark scenes
//! (`tools/instructions-per-pixel.sh`: the default cradle, 50 and 200 balls)
//! or per incremental frame of the default swing. The floor of the crate:
//! it imports nothing.

/// Tile edge in pixels: primary rays test only the objects whose screen
/// bounds cover their tile, and a packet's eight pixels share its lists.
/// Halved to 8x8, the default cradle took 427 instructions per pixel against
/// 404.
pub const TILE: u32 = 16;

/// A tile's candidate list holds at most this many objects; a packet whose
/// tile more reach is traced pixel by pixel.
pub const TILE_LIST_AT_MOST: usize = 16;

/// With the hierarchy on, scenes of at most this many bounded objects scan the
/// secondary rays' boxes eight at a time instead of walking it (a linear scan
/// for every scene was 2.1x worse at 50 balls).
pub const WIDE_AT_MOST: usize = 64;

/// Up to this many bounded objects the lanes' nearest hit scans the boxes over
/// the lanes (a run of up to eight at a time behind its hull); past it each
/// lane walks the hierarchy. 200 balls (612 objects) cost 2,493 instructions
/// per pixel scanning, 2,588 walking.
pub const SCAN_AT_MOST: usize = 1024;

/// Fewer lanes than this on one object are traced one by one, by the scalar
/// path: cheaper than the lanes for one (1: 416 and 433.8 instructions per
/// pixel against 411 to 415; 3: 547 against 540).
pub const SHARED: u32 = 2;

/// A run of eight pixels holding at least this many to re-trace goes as a
/// packet (which traces all eight); fewer go one by one. Per incremental
/// frame at one sample: 1 (always a packet) 167M instructions, 3 155M, 5 151M,
/// 6 150M, never 159M; anti-aliased, 4 1M more than 5 and 6 0.5M fewer.
pub const PACKET_AT_LEAST: usize = 6;

/// The motion filter finds a block's candidates this many blocks (of those
/// holding one) before it reads them, and then asks the CPU for the first
/// segment of each of the block's pixels (a hint: nothing else changes), so
/// that those segments, far apart in a row's buffer and rarely cached, are on
/// their way when it gets there. Chosen by time, which callgrind does not
/// see: medians of alternating pairs of `bench render --mode incremental` at
/// 1200x600 on an AMD EPYC, 1 thread, against asking for the pixel eight
/// ahead of each pixel walked: the realistic cradle 0.994x, the default
/// swing 0.959x (10 pairs each). Asking at 1 block ahead took 1.02x-1.03x
/// the time of 2 (realistic), at 4 1.01x; asking for the candidates' segments
/// alone, not the block's, 1.02x: a candidate's segments often reach past
/// their first cache line into the next pixel's.
pub const BLOCKS_AHEAD: usize = 2;

/// Blocks of a row's motion record per super-block: most blocks of a row meet
/// no moved cell, and scanning them all read 2.4 kB a row (a third of the
/// motion filter's cache misses).
pub const SUPER: usize = 8;

/// Objects per leaf of the hierarchy at most.
pub const BVH_LEAF: usize = 2;

/// Parts of the hierarchy holding more than this many runs of nearby objects
/// are cut into whole runs (each run costs its hull test): 200 balls 2,081 ->
/// 2,048 instructions per pixel.
pub const WHOLE_RUNS_PAST: usize = 8;

/// Segments a packet lane's buffer holds before it grows, in a tracked frame.
pub const LANE_SEGMENTS: usize = 16;
