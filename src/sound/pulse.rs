//! The Linux audio output: a playback stream on a server that speaks the
//! PulseAudio protocol (PulseAudio, or PipeWire's pulse server), through the
//! pure-Rust `pulseaudio` client over the server's Unix socket.
//!
//! The server clocks the stream: it asks for 10 ms at a time and keeps about
//! 40 ms queued, so a thread late to answer by up to 30 ms (a loaded 2-core
//! machine) never lets it run dry. Every 100 ms the thread asks the server how
//! far it has played, so that [`Device::wanted`] can say when the next frame is
//! heard.

use super::device::Device;
use super::synth::RATE;
use anyhow::{Context, bail};
use pulseaudio::protocol::{self, Command};
use std::ffi::CString;
use std::io::BufReader;
use std::os::unix::net::UnixStream;
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// Bytes of one frame: two 16-bit channels.
const FRAME_BYTES: u32 = 4;
/// What the stream keeps queued and what it asks for at a time (s).
const TARGET: f64 = 0.04;
const REQUEST: f64 = 0.01;
/// A server silent this long is gone (the thread then ends).
const TIMEOUT: Duration = Duration::from_secs(3);
/// The server's clock is asked after every this many writes (100 ms).
const CLOCK_EVERY: u64 = 10;

/// Tags of the requests whose replies the loop waits for.
const CREATE: u32 = 2;
const LATENCY: u32 = 3;

/// A playback stream on the server.
pub struct Pulse {
    sock: BufReader<UnixStream>,
    version: u16,
    channel: u32,
    /// Bytes the server asked for and has not been sent yet.
    asked: u32,
    /// Bytes written so far, in this many writes.
    written: u64,
    writes: u64,
    /// Reused for each write.
    bytes: Vec<u8>,
    /// From the last latency reply: when (s since the epoch) the byte at
    /// `heard` of the stream was being heard.
    clock: Option<(f64, f64)>,
    underruns: u64,
}

/// The server's socket: `$PULSE_SERVER` (unix:PATH), else `native` in
/// `$PULSE_RUNTIME_PATH`, `$XDG_RUNTIME_DIR/pulse` or `/run/user/UID/pulse`.
fn socket() -> anyhow::Result<PathBuf> {
    let server = std::env::var("PULSE_SERVER").ok();
    let mut tried = Vec::new();
    let candidates = server
        .iter()
        .filter_map(|s| s.strip_prefix("unix:").map(PathBuf::from))
        .chain(std::env::var_os("PULSE_RUNTIME_PATH").map(|p| PathBuf::from(p).join("native")))
        .chain(std::env::var_os("XDG_RUNTIME_DIR").map(|p| PathBuf::from(p).join("pulse/native")))
        .chain(user_runtime().map(|p| p.join("pulse/native")));
    for path in candidates {
        if path.exists() {
            return Ok(path);
        }
        tried.push(path.display().to_string());
    }
    if let Some(s) = server.filter(|s| !s.starts_with("unix:")) {
        bail!("no audio server: PULSE_SERVER={s} is not a local socket (unix:PATH)");
    }
    bail!(
        "no audio server (no PulseAudio or PipeWire socket at {})",
        if tried.is_empty() {
            "any known place".to_owned()
        } else {
            tried.join(", ")
        }
    )
}

/// `/run/user/UID`, the usual runtime folder, where the environment does not say.
fn user_runtime() -> Option<PathBuf> {
    use std::os::unix::fs::MetadataExt;
    let uid = std::fs::metadata("/proc/self").ok()?.uid();
    Some(PathBuf::from(format!("/run/user/{uid}")))
}

impl Pulse {
    /// Connects to the server and creates the stream.
    ///
    /// # Errors
    /// No server, or it refused the client or the stream.
    pub fn open() -> anyhow::Result<Self> {
        let path = socket()?;
        let stream = UnixStream::connect(&path)
            .with_context(|| format!("no audio server at {}", path.display()))?;
        stream.set_read_timeout(Some(TIMEOUT))?;
        stream.set_write_timeout(Some(TIMEOUT))?;
        let mut sock = BufReader::new(stream);
        let cookie = pulseaudio::cookie_path_from_env()
            .and_then(|p| std::fs::read(p).ok())
            .unwrap_or_default();
        let auth = protocol::AuthParams {
            version: protocol::MAX_VERSION,
            supports_shm: false,
            supports_memfd: false,
            cookie,
        };
        let refused = || format!("the audio server at {} refused the client", path.display());
        protocol::write_command_message(
            sock.get_mut(),
            0,
            &Command::Auth(auth),
            protocol::MAX_VERSION,
        )
        .with_context(refused)?;
        let (_, reply) =
            protocol::read_reply_message::<protocol::AuthReply>(&mut sock, protocol::MAX_VERSION)
                .with_context(refused)?;
        let version = protocol::MAX_VERSION.min(reply.version);
        let mut props = protocol::Props::new();
        props.set(
            protocol::Prop::ApplicationName,
            CString::new("newtons-cradle").expect("no NUL"),
        );
        protocol::write_command_message(sock.get_mut(), 1, &Command::SetClientName(props), version)
            .with_context(refused)?;
        protocol::read_reply_message::<protocol::SetClientNameReply>(&mut sock, version)
            .with_context(refused)?;
        let bytes = |s: f64| (s * f64::from(RATE)) as u32 * FRAME_BYTES;
        let params = protocol::PlaybackStreamParams {
            sample_spec: protocol::SampleSpec {
                format: protocol::SampleFormat::S16Le,
                channels: 2,
                sample_rate: RATE,
            },
            channel_map: protocol::ChannelMap::stereo(),
            cvolume: Some(protocol::ChannelVolume::norm(2)),
            sink_name: Some(protocol::DEFAULT_SINK.to_owned()),
            buffer_attr: protocol::stream::BufferAttr {
                max_length: u32::MAX,
                target_length: bytes(TARGET),
                pre_buffering: u32::MAX,
                minimum_request_length: bytes(REQUEST),
                fragment_size: u32::MAX,
            },
            flags: protocol::stream::StreamFlags {
                adjust_latency: true,
                ..Default::default()
            },
            ..Default::default()
        };
        protocol::write_command_message(
            sock.get_mut(),
            CREATE,
            &Command::CreatePlaybackStream(params),
            version,
        )
        .context("the audio server refused the stream")?;
        let (_, stream) =
            protocol::read_reply_message::<protocol::CreatePlaybackStreamReply>(&mut sock, version)
                .context("the audio server refused the stream")?;
        tracing::info!(
            "sound: playing on {} at {} Hz",
            stream
                .sink_name
                .as_ref()
                .map_or_else(|| "the default output".into(), |s| s.to_string_lossy()),
            RATE
        );
        Ok(Self {
            sock,
            version,
            channel: stream.channel,
            asked: stream.requested_bytes,
            written: 0,
            writes: 0,
            bytes: Vec::new(),
            clock: None,
            underruns: 0,
        })
    }

    /// When (s since `epoch`) the next byte written will be heard.
    fn next_heard(&self, epoch: Instant) -> f64 {
        let bps = f64::from(RATE * FRAME_BYTES);
        match self.clock {
            Some((at, heard)) => at + (self.written as f64 - heard) / bps,
            // Before the server has said: a full queue ahead.
            None => epoch.elapsed().as_secs_f64() + TARGET,
        }
    }
}

impl Device for Pulse {
    fn wanted(&mut self, epoch: Instant) -> anyhow::Result<(usize, f64)> {
        while self.asked < FRAME_BYTES {
            let (seq, msg) = protocol::read_command_message(&mut self.sock, self.version)
                .context("the audio server went away")?;
            match msg {
                Command::Request(r) if r.channel == self.channel => self.asked += r.length,
                Command::Reply if seq == LATENCY => {
                    let now = epoch.elapsed().as_secs_f64();
                    let mut ts = protocol::TagStructReader::new(&mut self.sock, self.version);
                    let l = ts
                        .read::<protocol::PlaybackLatency>()
                        .context("the audio server's timing")?;
                    // The sink has read up to `read_offset`; what it holds plays
                    // over the next `sink_usec`.
                    let bps = f64::from(RATE * FRAME_BYTES);
                    let heard = l.read_offset as f64 - l.sink_usec as f64 * 1e-6 * bps;
                    self.clock = Some((now, heard));
                }
                Command::Underflow(_) => {
                    self.underruns += 1;
                    tracing::debug!(
                        "sound: underrun {} after {:.3} s of sound",
                        self.underruns,
                        self.written as f64 / f64::from(RATE * FRAME_BYTES)
                    );
                }
                Command::Error(e) => bail!("the audio server failed: {e:?}"),
                Command::PlaybackStreamKilled(_) => bail!("the audio server closed the stream"),
                _ => {}
            }
        }
        let frames = (self.asked / FRAME_BYTES) as usize;
        Ok((frames, self.next_heard(epoch)))
    }

    fn write(&mut self, samples: &[i16]) -> anyhow::Result<()> {
        self.bytes.clear();
        self.bytes
            .extend(samples.iter().flat_map(|s| s.to_le_bytes()));
        protocol::write_memblock(self.sock.get_mut(), self.channel, &self.bytes, 0)
            .context("the audio server went away")?;
        self.asked = self.asked.saturating_sub(self.bytes.len() as u32);
        self.written += self.bytes.len() as u64;
        self.writes += 1;
        if self.writes % CLOCK_EVERY != 1 {
            return Ok(());
        }
        protocol::write_command_message(
            self.sock.get_mut(),
            LATENCY,
            &Command::GetPlaybackLatency(protocol::LatencyParams {
                channel: self.channel,
                now: std::time::SystemTime::now(),
            }),
            self.version,
        )
        .context("the audio server went away")?;
        Ok(())
    }

    fn underruns(&self) -> u64 {
        self.underruns
    }
}
