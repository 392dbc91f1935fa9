//! Opening a gamepad and reading it on its own thread: an event device
//! (`/dev/input/eventN`, through the `evdev` crate's raw stream: its axes'
//! ranges, and a drop (`SYN_DROPPED`) seen as the kernel reports it, not
//! resynchronised behind our back), or any file or named pipe
//! that carries `struct input_event` records (a remote stick forwarded over a
//! pipe, a recording, a test). Each frame's state, a drop, or the end is sent
//! on a channel the moment it is read.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::time::Instant;

use crossbeam_channel::Receiver;

use super::event::{EVENT_SIZE, RawEvent};
use super::state::{PadState, Step};
use crate::link::Waker;

/// Why a gamepad stopped being read.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum Gone {
    /// The file or pipe ended (its writer closed it).
    #[error("the gamepad's input ended (end of file)")]
    Ended,
    /// The device went away (`ENODEV`: unplugged, out of range).
    #[error("the gamepad was unplugged or went out of range; plug it in and pick it again")]
    Unplugged,
    /// Reading failed otherwise.
    #[error("reading the gamepad failed: {0}; pick it again once it is back")]
    Failed(String),
    /// It could not be opened.
    #[error(
        "cannot open the gamepad {path}: {error}. Is the path right (the Gamepad tab lists the gamepads this computer has), and may you read it (Linux: the `input` group)?"
    )]
    Open {
        /// The path.
        path: String,
        /// Why.
        error: String,
    },
}

/// What the reading thread says, with when it read it.
#[derive(Clone, Debug, PartialEq)]
pub enum PadUpdate {
    /// A frame ended: the state now.
    State(PadState),
    /// Events were lost: the state is unknown until the next frame ends.
    Dropped,
    /// The gamepad cannot be read any more.
    Gone(Gone),
}

/// A gamepad being read.
#[derive(Debug)]
pub struct Gamepad {
    /// What it is called (its device name, or the path's file name).
    pub name: String,
    /// Where it was opened.
    pub path: PathBuf,
    updates: Receiver<(Instant, PadUpdate)>,
}

/// A gamepad this computer has.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct GamepadInfo {
    /// Its event device.
    pub path: PathBuf,
    /// Its name.
    pub name: String,
}

impl Gamepad {
    /// Starts reading `path`: an event device, or a file or pipe of
    /// `input_event` records whose axes span `range` (default
    /// −32768..32767). Opening happens on the reading thread (a named pipe
    /// waits for its writer): a failure arrives as [`Gone::Open`].
    pub fn open(path: &Path, range: Option<(i32, i32)>, waker: Waker) -> std::io::Result<Self> {
        let (sender, updates) = crossbeam_channel::unbounded();
        let name = path.file_name().map_or_else(|| path.display().to_string(), |n| n.to_string_lossy().into_owned());
        let owned = path.to_path_buf();
        std::thread::Builder::new().name(format!("gamepad {}", path.display())).spawn(move || {
            let send = |update: PadUpdate| {
                let sent = sender.send((Instant::now(), update)).is_ok();
                waker();
                sent
            };
            read(&owned, range, &send);
        })?;
        Ok(Self { name, path: path.to_path_buf(), updates })
    }

    /// Every update as it is read.
    pub fn updates(&self) -> &Receiver<(Instant, PadUpdate)> {
        &self.updates
    }
}

/// Reads `path` until it ends or nobody listens.
fn read(path: &Path, range: Option<(i32, i32)>, send: &dyn Fn(PadUpdate) -> bool) {
    #[cfg(target_os = "linux")]
    {
        use std::os::unix::fs::FileTypeExt;
        if std::fs::metadata(path).is_ok_and(|metadata| metadata.file_type().is_char_device()) {
            return linux::read_device(path, send);
        }
    }
    #[cfg(not(target_os = "linux"))]
    if let Some(id) = path.to_str().and_then(|path| path.strip_prefix(other::PREFIX)).and_then(|id| id.parse().ok()) {
        return other::read_pad(id, send);
    }
    let file = match std::fs::File::open(path) {
        Ok(file) => file,
        Err(error) => {
            send(PadUpdate::Gone(Gone::Open { path: path.display().to_string(), error: error.to_string() }));
            return;
        }
    };
    read_records(file, PadState::new(range.unwrap_or(super::state::DEFAULT_RANGE)), send);
}

/// Reads `input_event` records from `source` into `state`, telling each frame.
pub fn read_records(mut source: impl Read, mut state: PadState, send: &dyn Fn(PadUpdate) -> bool) {
    let mut record = [0u8; EVENT_SIZE];
    loop {
        match source.read_exact(&mut record) {
            Ok(()) => {}
            Err(error) if error.kind() == std::io::ErrorKind::UnexpectedEof => {
                send(PadUpdate::Gone(Gone::Ended));
                return;
            }
            Err(error) if error.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(error) => {
                send(PadUpdate::Gone(gone(&error)));
                return;
            }
        }
        if !tell(&mut state, RawEvent::from_bytes(&record), send) {
            return;
        }
    }
}

/// Applies one event; tells what it did. False when nobody listens any more.
fn tell(state: &mut PadState, event: RawEvent, send: &dyn Fn(PadUpdate) -> bool) -> bool {
    match state.apply(event) {
        Step::Pending => true,
        Step::Dropped => send(PadUpdate::Dropped),
        Step::Frame | Step::Resynced => send(PadUpdate::State(state.clone())),
    }
}

fn gone(error: &std::io::Error) -> Gone {
    // ENODEV (19): the device was removed.
    if error.raw_os_error() == Some(19) { Gone::Unplugged } else { Gone::Failed(error.to_string()) }
}

/// The gamepads this computer has (event devices with a stick and gamepad or joystick buttons).
pub fn list() -> Vec<GamepadInfo> {
    #[cfg(target_os = "linux")]
    {
        linux::list()
    }
    #[cfg(not(target_os = "linux"))]
    {
        other::list()
    }
}

/// Other systems: a thin adapter over `gilrs` (not yet verified on those
/// systems). Its buttons and axes are given the kernel's codes (the left
/// shoulder is `BTN_TL`, the left stick `ABS_X`/`ABS_Y`, up low as on Linux),
/// so bindings and the dead-man mean the same everywhere. A pad is named
/// `gilrs:N` where Linux names an event device.
#[cfg(not(target_os = "linux"))]
mod other {
    use super::*;
    use crate::gamepad::event::{
        ABS_RX, ABS_RY, ABS_RZ, ABS_X, ABS_Y, ABS_Z, BTN_EAST, BTN_NORTH, BTN_SELECT, BTN_SOUTH, BTN_START, BTN_TL,
        BTN_TR, BTN_WEST,
    };

    /// How a gamepad is named in place of a path.
    pub(super) const PREFIX: &str = "gilrs:";

    pub(super) fn list() -> Vec<GamepadInfo> {
        let Ok(gilrs) = gilrs::Gilrs::new() else { return Vec::new() };
        gilrs
            .gamepads()
            .map(|(id, pad)| GamepadInfo {
                path: PathBuf::from(format!("{PREFIX}{}", usize::from(id))),
                name: pad.name().to_string(),
            })
            .collect()
    }

    fn button(button: gilrs::Button) -> Option<u16> {
        use gilrs::Button as B;
        Some(match button {
            B::South => BTN_SOUTH,
            B::East => BTN_EAST,
            B::North => BTN_NORTH,
            B::West => BTN_WEST,
            B::LeftTrigger => BTN_TL,
            B::RightTrigger => BTN_TR,
            B::Select => BTN_SELECT,
            B::Start => BTN_START,
            _ => return None,
        })
    }

    /// The kernel's code, and whether up (gilrs: positive) is the axis's low end.
    fn axis(axis: gilrs::Axis) -> Option<(u16, bool)> {
        use gilrs::Axis as A;
        Some(match axis {
            A::LeftStickX => (ABS_X, false),
            A::LeftStickY => (ABS_Y, true),
            A::RightStickX => (ABS_RX, false),
            A::RightStickY => (ABS_RY, true),
            A::LeftZ => (ABS_Z, false),
            A::RightZ => (ABS_RZ, false),
            _ => return None,
        })
    }

    pub(super) fn read_pad(wanted: usize, send: &dyn Fn(PadUpdate) -> bool) {
        let mut gilrs = match gilrs::Gilrs::new() {
            Ok(gilrs) => gilrs,
            Err(error) => {
                send(PadUpdate::Gone(Gone::Open { path: format!("{PREFIX}{wanted}"), error: error.to_string() }));
                return;
            }
        };
        let mut state = PadState::default();
        loop {
            let Some(event) = gilrs.next_event_blocking(Some(std::time::Duration::from_millis(200))) else {
                continue;
            };
            if usize::from(event.id) != wanted {
                continue;
            }
            let raw = match event.event {
                gilrs::EventType::ButtonPressed(pressed, _) => button(pressed).map(|code| RawEvent::key(code, true)),
                gilrs::EventType::ButtonReleased(released, _) => {
                    button(released).map(|code| RawEvent::key(code, false))
                }
                gilrs::EventType::AxisChanged(moved, value, _) => axis(moved).map(|(code, flip)| {
                    let value = if flip { -value } else { value };
                    // −1..1 onto the range a path's axes are taken to span.
                    #[allow(clippy::cast_possible_truncation)]
                    let raw = (f64::from(value.clamp(-1.0, 1.0)) * 32767.0).round() as i32;
                    RawEvent::abs(code, raw)
                }),
                gilrs::EventType::Disconnected => {
                    send(PadUpdate::Gone(Gone::Unplugged));
                    return;
                }
                _ => None,
            };
            if let Some(raw) = raw
                && !(tell(&mut state, raw, send) && tell(&mut state, RawEvent::report(), send))
            {
                return;
            }
        }
    }
}

#[cfg(target_os = "linux")]
mod linux {
    use super::*;

    /// Buttons only gamepads and joysticks have (`BTN_SOUTH`, `BTN_TRIGGER`).
    const PAD_BUTTONS: [u16; 2] = [0x130, 0x120];

    pub(super) fn list() -> Vec<GamepadInfo> {
        evdev::enumerate()
            .filter(|(_, device)| {
                let buttons = device
                    .supported_keys()
                    .is_some_and(|keys| PAD_BUTTONS.iter().any(|code| keys.contains(evdev::KeyCode(*code))));
                let stick = device
                    .supported_absolute_axes()
                    .is_some_and(|axes| axes.contains(evdev::AbsoluteAxisCode(super::super::event::ABS_X)));
                buttons && stick
            })
            .map(|(path, device)| GamepadInfo { name: device.name().unwrap_or("gamepad").to_string(), path })
            .collect()
    }

    pub(super) fn read_device(path: &Path, send: &dyn Fn(PadUpdate) -> bool) {
        // The raw stream, not the crate's synchronised `Device`: that one
        // swallows SYN_DROPPED and replays the state it reads back, so a
        // dead-man held across a drop would read held without a fresh press.
        // Read raw, a drop reaches `PadState` as it does from a pipe.
        let mut device = match evdev::raw_stream::RawDevice::open(path) {
            Ok(device) => device,
            Err(error) => {
                send(PadUpdate::Gone(Gone::Open { path: path.display().to_string(), error: error.to_string() }));
                return;
            }
        };
        let mut state = PadState::default();
        if let Ok(axes) = device.get_absinfo() {
            for (axis, info) in axes {
                state.set_range(axis.0, (info.minimum(), info.maximum()));
            }
        }
        read_batches(
            || {
                device.fetch_events().map(|events| {
                    events
                        .map(|event| RawEvent { kind: event.event_type().0, code: event.code(), value: event.value() })
                        .collect()
                })
            },
            state,
            send,
        );
    }
}

/// Reads batches of events (as an event device hands them over, a read at a
/// time) into `state`, telling each frame, until the source fails or nobody
/// listens.
pub fn read_batches(
    mut fetch: impl FnMut() -> std::io::Result<Vec<RawEvent>>,
    mut state: PadState,
    send: &dyn Fn(PadUpdate) -> bool,
) {
    loop {
        let events = match fetch() {
            Ok(events) => events,
            Err(error) if error.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(error) => {
                send(PadUpdate::Gone(gone(&error)));
                return;
            }
        };
        for event in events {
            if !tell(&mut state, event, send) {
                return;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::event::{ABS_Y, BTN_TL, EV_KEY};
    use super::*;

    /// Records as the kernel writes them, built here byte by byte: each frame
    /// is told at its SYN_REPORT, a drop at once, and a record cut short at
    /// the end is the end of the input.
    #[test]
    fn records_are_read_frame_by_frame_and_a_cut_record_ends_the_input() {
        let mut bytes = Vec::new();
        for event in [RawEvent::key(BTN_TL, true), RawEvent::abs(ABS_Y, -32768), RawEvent::report()] {
            bytes.extend(event.to_bytes(1_000));
        }
        bytes.extend(RawEvent::dropped().to_bytes(2_000));
        // A key event with a value of 2 (auto-repeat) is held, as 1 is.
        let mut repeat = RawEvent::key(BTN_TL, true);
        repeat.value = 2;
        assert_eq!(repeat.kind, EV_KEY);
        for event in [repeat, RawEvent::report(), RawEvent::report()] {
            bytes.extend(event.to_bytes(3_000));
        }
        bytes.extend(&RawEvent::report().to_bytes(4_000)[..10]);
        let told = std::cell::RefCell::new(Vec::new());
        read_records(bytes.as_slice(), PadState::default(), &|update| {
            told.borrow_mut().push(update);
            true
        });
        let told = told.into_inner();
        assert_eq!(told.len(), 5, "{told:?}");
        let PadUpdate::State(first) = &told[0] else { panic!("{told:?}") };
        assert!(first.pressed(BTN_TL) && first.axis(ABS_Y) == -1.0);
        assert_eq!(told[1], PadUpdate::Dropped);
        let (PadUpdate::State(torn), PadUpdate::State(after)) = (&told[2], &told[3]) else { panic!("{told:?}") };
        assert!(!torn.pressed(BTN_TL), "the frame that ends a drop is discarded");
        assert!(!after.pressed(BTN_TL) && after.known());
        assert_eq!(told[4], PadUpdate::Gone(Gone::Ended));
    }

    /// An event device read a batch at a time, as `evdev`'s raw stream hands
    /// the kernel's buffer over (SYN_DROPPED included, nothing replayed): a
    /// drop arrives mid-batch, and a dead-man held through it sends no new
    /// event. The base stops at the drop and does not drive while the stick
    /// moves on: only a dead-man let go and pressed again drives.
    #[test]
    fn a_drop_on_an_event_device_stops_the_base_until_a_fresh_press() {
        use super::super::event::{ABS_Y, BTN_TL};
        use super::super::teleop::{Order, StopReason, Teleop, TeleopConfig};
        let held = [RawEvent::key(BTN_TL, true), RawEvent::abs(ABS_Y, -32768), RawEvent::report()];
        let mut batches = vec![
            // Held and driving; then the buffer overran: a drop, and the torn frame after it.
            held.to_vec(),
            vec![RawEvent::abs(ABS_Y, -30000), RawEvent::dropped(), RawEvent::abs(ABS_Y, -32000), RawEvent::report()],
            // Still held (no key event: nothing changed), the stick full again.
            vec![RawEvent::abs(ABS_Y, -32768), RawEvent::report()],
            // Let go, then pressed again.
            vec![RawEvent::key(BTN_TL, false), RawEvent::report()],
            held.to_vec(),
        ]
        .into_iter();
        let told = std::cell::RefCell::new(Vec::new());
        read_batches(
            || batches.next().ok_or_else(|| std::io::Error::from_raw_os_error(19)),
            PadState::default(),
            &|update| {
                told.borrow_mut().push(update);
                true
            },
        );
        let told = told.into_inner();
        assert_eq!(told.last(), Some(&PadUpdate::Gone(Gone::Unplugged)), "ENODEV: unplugged");
        let t0 = Instant::now();
        let mut teleop = Teleop::new(TeleopConfig::default());
        let orders: Vec<Option<Order>> = told
            .iter()
            .enumerate()
            .map(|(index, update)| teleop.update(t0 + std::time::Duration::from_secs(index as u64), update))
            .collect();
        let drive = Some(Order::Drive { speed_m_per_s: 0.5, turn_rad_per_s: 0.0 });
        assert_eq!(orders[0], drive, "{told:?}");
        assert_eq!(told[1], PadUpdate::Dropped);
        assert_eq!(orders[1], Some(Order::Stop(StopReason::Dropped)));
        assert!(orders[2..5].iter().all(Option::is_none), "no drive after the drop until a fresh press: {orders:?}");
        assert!(matches!(&told[3], PadUpdate::State(after) if after.axis(ABS_Y) == -1.0), "{told:?}");
        assert_eq!(orders[5], drive, "pressed again: drives ({told:?})");
        assert_eq!(orders[6], Some(Order::Stop(StopReason::Gone)));
    }
}
