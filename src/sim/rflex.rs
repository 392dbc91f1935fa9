//! The emulated rFLEX base: the server side of `rflex.md` over the same codec.
//! Commanded velocities are integrated with their acceleration limits into
//! odometry reports at the requested period; the robot's own sonars (its
//! layout, rflex.md §6: banks, mounts, bearings, range scale) measure a
//! rectangular room, reported a bank at a time; the battery falls slowly; its
//! bumpers (B21r panels, Magellan bits) can be pressed; the base starts braked and never moves while
//! braked; a dead-man timeout stops it when motion commands stop arriving.
//! Output can be stuffed and salted with line noise (garbage, corrupted and
//! cut frames), each counted, so a test knows where it lands.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use crossbeam_channel::Sender;

use super::faults::{LineNoise, hits};
use crate::link::Driver;
use crate::protocol::rflex::layout::{Bumps, Transducer};
use crate::protocol::rflex::{Axis, B21R, Command, Conversion, DecoderEvent, FrameDecoder, Report, SonarReading};
/// How often one bank of the sonar ring reports while the sonar runs.
const SONAR_BANK_EVERY: Duration = Duration::from_millis(50);

/// How the emulated base behaves.
#[derive(Clone, Debug, PartialEq)]
pub struct RflexSimConfig {
    /// The robot's conversion constants.
    pub conversion: Conversion,
    /// Send frames stuffed.
    pub stuffed: bool,
    /// Noise on the output.
    pub noise: LineNoise,
    /// Stop when no motion command came for this long.
    pub dead_man: Duration,
    /// Battery at power-on, volts.
    pub battery_volts: f64,
    /// Battery drain while standing, volts per second (more while moving).
    pub drain_volts_per_s: f64,
    /// The room, metres (width along x, depth along y), its centre the origin.
    pub room_m: (f64, f64),
    /// Where the base starts: x and y from the room's centre, metres, and its heading, radians from +x.
    pub start: (f64, f64, f64),
    /// Report only a B21r's six body panels (0x40–0x45), for the ROS `b21_node`,
    /// which aborts on its base panels (rflex.md §6).
    pub body_panels_only: bool,
}

impl Default for RflexSimConfig {
    fn default() -> Self {
        Self {
            conversion: B21R,
            stuffed: false,
            noise: LineNoise::default(),
            dead_man: Duration::from_millis(500),
            battery_volts: 26.4,
            drain_volts_per_s: 0.002,
            room_m: (4.2, 2.8),
            start: (0.0, 0.0, 0.0),
            body_panels_only: false,
        }
    }
}

/// The base's state, as a test inspects it.
#[derive(Clone, Debug, PartialEq)]
pub struct BaseState {
    /// The brake is set.
    pub braked: bool,
    /// Translational velocity, m/s.
    pub speed_m_per_s: f64,
    /// The translational velocity it is heading for, m/s.
    pub target_speed_m_per_s: f64,
    /// Rotational velocity, rad/s.
    pub turn_rad_per_s: f64,
    /// Distance driven (the odometer), m.
    pub distance_m: f64,
    /// Position in the room, m (the start is the room's middle).
    pub x_m: f64,
    /// Position in the room, m.
    pub y_m: f64,
    /// Heading, rad.
    pub theta_rad: f64,
    /// Battery, volts.
    pub battery_volts: f64,
    /// Motion commands received.
    pub motion_commands: u64,
    /// What each sonar measures now, metres after the raw quantisation (`None` = no echo), by id.
    pub sonar_m: std::collections::BTreeMap<u8, Option<f64>>,
}

/// What the owner tells the emulated base.
#[derive(Debug)]
pub enum RflexSimCommand {
    /// Press (`corners` ≠ 0) or release a bumper: `panel` counts the robot's
    /// bump addresses from the first (B21r: a panel, `corners` its low 4 bits;
    /// Magellan: a byte of 8 bumpers, `corners` their bits).
    Bump {
        /// The panel (the address's offset).
        panel: u8,
        /// The data: pressed corners or bumper bits.
        corners: u16,
    },
    /// Move the joystick.
    Joystick {
        /// Stick x.
        x: i32,
        /// Stick y.
        y: i32,
        /// Buttons.
        buttons: u8,
    },
    /// Report the state now.
    Inspect(Sender<BaseState>),
    /// Close the client's link (a pulled cable).
    Disconnect,
}

/// What the emulated base reports to its owner.
#[derive(Clone, Debug, PartialEq)]
pub enum RflexSimEvent {
    /// A command arrived.
    Received(Command),
    /// The dead-man timeout stopped a moving base.
    DeadManStop,
}

#[derive(Clone, Copy, Debug, Default)]
struct AxisState {
    /// Signed target, units/s.
    target: f64,
    /// Units/s².
    acceleration: f64,
    velocity: f64,
    position: f64,
}

impl AxisState {
    /// Advances `dt` seconds: the velocity ramps to the target at the acceleration.
    fn advance(&mut self, dt: f64, target: f64) {
        let gap = target - self.velocity;
        let rate = self.acceleration.max(0.0);
        if rate == 0.0 {
            self.position += self.velocity * dt;
            return;
        }
        let reach = gap.abs() / rate;
        if reach <= dt {
            let v0 = self.velocity;
            self.position += (v0 + target) / 2.0 * reach + target * (dt - reach);
            self.velocity = target;
        } else {
            let v1 = self.velocity + gap.signum() * rate * dt;
            self.position += (self.velocity + v1) / 2.0 * dt;
            self.velocity = v1;
        }
    }
}

/// The emulated base; a [`Driver`], so the runners serve it anywhere.
#[derive(Debug)]
pub struct RflexSim {
    config: RflexSimConfig,
    decoder: FrameDecoder,
    started: Option<Instant>,
    last_tick: Option<Instant>,
    translation: AxisState,
    rotation: AxisState,
    braked: bool,
    last_motion: Option<Instant>,
    motion_commands: u64,
    odometry: Option<(Duration, u32, Instant)>,
    dio: Option<(Duration, Instant)>,
    sonar_next: Option<(u8, Instant)>,
    bumpers: Vec<u16>,
    joystick: (i32, i32, u8),
    battery_volts: f64,
    world: (f64, f64, f64),
    frames_sent: u64,
    running_number: u8,
    output: VecDeque<Vec<u8>>,
    events: VecDeque<RflexSimEvent>,
    close: bool,
    /// The bumper pressed against a wall, if any: its index and the data it showed.
    wall_contact: Option<(usize, u16)>,
}

impl RflexSim {
    /// A base at rest, braked, where its config starts it.
    pub fn new(config: RflexSimConfig) -> Self {
        let battery_volts = config.battery_volts;
        let bumpers = vec![0; config.conversion.layout.bump_addresses().len()];
        let world = config.start;
        Self {
            config,
            decoder: FrameDecoder::new(),
            started: None,
            last_tick: None,
            translation: AxisState::default(),
            rotation: AxisState::default(),
            braked: true,
            last_motion: None,
            motion_commands: 0,
            odometry: None,
            dio: None,
            sonar_next: None,
            bumpers,
            joystick: (0, 0, 0),
            battery_volts,
            world,
            frames_sent: 0,
            running_number: 0,
            output: VecDeque::new(),
            events: VecDeque::new(),
            close: false,
            wall_contact: None,
        }
    }

    fn timestamp(&self, now: Instant) -> u32 {
        let ms = self.started.map_or(0, |start| now.saturating_duration_since(start).as_millis());
        // The base's clock wraps like its 32-bit counter.
        #[allow(clippy::cast_possible_truncation)]
        let wrapped = ms as u32;
        wrapped
    }

    /// Integrates motion up to `now`.
    fn tick(&mut self, now: Instant) {
        self.started.get_or_insert(now);
        let last = *self.last_tick.get_or_insert(now);
        let dt = now.saturating_duration_since(last).as_secs_f64();
        self.last_tick = Some(now);
        if dt <= 0.0 {
            return;
        }
        if self.braked {
            self.translation.velocity = 0.0;
            self.rotation.velocity = 0.0;
        } else {
            let conversion = self.config.conversion;
            let before = (self.translation.position, self.rotation.position);
            self.translation.advance(dt, self.translation.target);
            self.rotation.advance(dt, self.rotation.target);
            let d = (self.translation.position - before.0) / conversion.distance_units_per_m;
            let turned = (self.rotation.position - before.1) / conversion.angle_units_per_rad;
            let (x, y, theta) = self.world;
            let heading = theta + turned / 2.0;
            self.world = (x + d * heading.cos(), y + d * heading.sin(), theta + turned);
            self.walls(d);
        }
        let moving = self.translation.velocity.abs() / self.config.conversion.distance_units_per_m;
        self.battery_volts -= dt * self.config.drain_volts_per_s * (1.0 + 4.0 * moving);
        // The dead-man: no motion command for a while stops the base.
        if let Some(last) = self.last_motion
            && now.saturating_duration_since(last) >= self.config.dead_man
            && (self.translation.target != 0.0 || self.rotation.target != 0.0)
        {
            self.translation.target = 0.0;
            self.rotation.target = 0.0;
            self.events.push_back(RflexSimEvent::DeadManStop);
        }
    }

    /// A base that reaches a wall stops there with the bumper that hit it pressed
    /// (front when driving forward, back when reversing); moving away releases it.
    fn walls(&mut self, moved_m: f64) {
        let (width, height) = self.config.room_m;
        let (x, y, theta) = self.world;
        let radius = self.config.conversion.layout.body_radius_m;
        let (max_x, max_y) = ((width / 2.0 - radius).max(0.0), (height / 2.0 - radius).max(0.0));
        let clamped = (x.clamp(-max_x, max_x), y.clamp(-max_y, max_y));
        if clamped != (x, y) {
            self.world = (clamped.0, clamped.1, theta);
            self.translation.velocity = 0.0;
            self.translation.target = 0.0;
            if let Some((index, data)) = self.contact(moved_m >= 0.0) {
                self.bumpers[index] |= data;
                self.wall_contact = Some((index, data));
            }
        } else if let Some((index, data)) = self.wall_contact.take() {
            // Off the wall again.
            self.bumpers[index] &= !data;
        }
    }

    /// The bumper a wall presses (its index among the bump addresses, and its
    /// data): choice — a B21r's body panel 0 faces ahead and panel 3 behind, a
    /// Magellan's bumper 0 ahead and bumper 8 behind; an ATRV-Jr has none.
    fn contact(&self, front: bool) -> Option<(usize, u16)> {
        match self.config.conversion.layout.bumps {
            Bumps::Panels { count, .. } => Some((if front { 0 } else { usize::from(count.min(6) / 2) }, 0b0011)),
            Bumps::Bits { bytes, .. } => Some((if front { 0 } else { usize::from(bytes.saturating_sub(1)) }, 1)),
            Bumps::None => None,
        }
    }

    fn send(&mut self, report: &Report) {
        self.running_number = self.running_number.wrapping_add(1);
        let frame = report.to_frame(self.running_number);
        let encoded = if self.config.stuffed { frame.to_stuffed_bytes() } else { frame.to_bytes() };
        let Ok(mut bytes) = encoded else { return };
        self.frames_sent += 1;
        let count = self.frames_sent;
        let noise = &self.config.noise;
        if hits(noise.garbage_every, count) {
            // Noise with half a frame start in it.
            self.output.push_back(vec![0x00, 0xff, 0x1b, 0x55, 0x7c, 0x02, 0x1b]);
        }
        if hits(noise.corrupt_every, count) && bytes.len() > 7 {
            bytes[6] ^= 0x5a;
        }
        if hits(noise.cut_every, count) {
            bytes.truncate(bytes.len() / 2);
        }
        self.output.push_back(bytes);
    }

    fn odometry_report(&mut self, now: Instant, mask: u32) {
        let timestamp = self.timestamp(now);
        for (axis, state) in [(Axis::Translation, self.translation), (Axis::Rotation, self.rotation)] {
            if mask & (1 << axis.code()) == 0 {
                continue;
            }
            // The counters wrap like the base's 32-bit registers.
            #[allow(clippy::cast_possible_truncation)]
            let (position, velocity) = (state.position as i64 as i32, state.velocity as i32);
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            let acceleration = state.acceleration as u32;
            self.send(&Report::Odometry {
                unknown: 0,
                timestamp,
                axis: axis.code(),
                position,
                velocity,
                acceleration,
                torque: 0,
            });
        }
    }

    /// The range `transducer` measures to the room's walls, raw: from its
    /// mount along its bearing, at the robot's range scale.
    fn sonar_range(&self, transducer: &Transducer) -> u16 {
        let (x, y, theta) = self.world;
        let (width, height) = self.config.room_m;
        let (sin, cos) = theta.sin_cos();
        let (mx, my) = transducer.mount_m;
        let (ox, oy) = (x + mx * cos - my * sin, y + mx * sin + my * cos);
        let angle = theta + transducer.bearing_rad;
        let (dx, dy) = (angle.cos(), angle.sin());
        let mut distance = f64::INFINITY;
        for (d, position, half) in [(dx, ox, width / 2.0), (dy, oy, height / 2.0)] {
            if d > 1e-9 {
                distance = distance.min((half - position) / d);
            } else if d < -1e-9 {
                distance = distance.min((-half - position) / d);
            }
        }
        let units = (distance.max(0.0) * self.config.conversion.layout.raw_per_m).round();
        // Saturates at the field's maximum: beyond 3000 means no echo anyway.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let range = units.min(f64::from(u16::MAX)) as u16;
        range
    }

    /// The readings of one of the robot's banks.
    fn sonar_bank(&mut self, now: Instant, bank: u8) {
        let layout = self.config.conversion.layout;
        let readings = layout
            .bank_ids(bank)
            .filter_map(|id| layout.transducer(id))
            .map(|transducer| SonarReading { sonar_id: transducer.id, range: self.sonar_range(&transducer) })
            .collect();
        let timestamp = self.timestamp(now);
        self.send(&Report::Sonar { unknown: 0, timestamp, readings });
    }

    fn handle(&mut self, now: Instant, command: Command) {
        let conversion = self.config.conversion;
        match &command {
            Command::SystemStatus => {
                let raw = ((self.battery_volts - conversion.power_offset_volts) * 100.0).round().max(0.0);
                #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
                let voltage_raw = raw as u32;
                let timestamp = self.timestamp(now);
                self.send(&Report::Status { timestamp, voltage_raw, brake: u8::from(self.braked) });
            }
            Command::JoystickState => {
                let (x, y, buttons) = self.joystick;
                let timestamp = self.timestamp(now);
                self.send(&Report::Joystick { timestamp, x, y, buttons });
            }
            Command::OdometryReports { period_us, axis_mask } => {
                self.odometry = (*period_us > 0 && *axis_mask != 0).then(|| {
                    let period = Duration::from_micros(u64::from(*period_us));
                    (period, *axis_mask, now + period)
                });
            }
            Command::MotionDefaults => {
                self.translation.target = 0.0;
                self.rotation.target = 0.0;
            }
            Command::BrakeSet => {
                self.braked = true;
                self.translation.target = 0.0;
                self.rotation.target = 0.0;
                self.translation.velocity = 0.0;
                self.rotation.velocity = 0.0;
            }
            Command::BrakeRelease => self.braked = false,
            Command::AxisSetDir { axis, speed, acceleration, direction, .. } => {
                self.motion_commands += 1;
                self.last_motion = Some(now);
                let signed = if *direction == 0 { -f64::from(*speed) } else { f64::from(*speed) };
                let state = match Axis::from_code(*axis) {
                    Some(Axis::Translation) => &mut self.translation,
                    Some(Axis::Rotation) => &mut self.rotation,
                    None => return,
                };
                state.target = if self.braked { 0.0 } else { signed };
                state.acceleration = f64::from(*acceleration);
            }
            Command::AxisSetPos { .. } | Command::IrRun { .. } | Command::Unknown(_) => {}
            Command::SonarRun { mode, .. } => {
                self.sonar_next = (*mode != 0).then_some((0, now));
            }
            Command::DioReports { period_us } => {
                self.dio = (*period_us > 0).then(|| {
                    let period = Duration::from_micros(u64::from(*period_us));
                    (period, now + period)
                });
            }
        }
        self.events.push_back(RflexSimEvent::Received(command));
    }

    /// The state now.
    pub fn state(&self) -> BaseState {
        let conversion = self.config.conversion;
        BaseState {
            braked: self.braked,
            speed_m_per_s: self.translation.velocity / conversion.distance_units_per_m,
            target_speed_m_per_s: self.translation.target / conversion.distance_units_per_m,
            turn_rad_per_s: self.rotation.velocity / conversion.angle_units_per_rad,
            distance_m: self.translation.position / conversion.distance_units_per_m,
            x_m: self.world.0,
            y_m: self.world.1,
            theta_rad: self.world.2,
            battery_volts: self.battery_volts,
            motion_commands: self.motion_commands,
            sonar_m: {
                let layout = self.config.conversion.layout;
                layout.transducers().iter().map(|t| (t.id, layout.range_m(self.sonar_range(t)))).collect()
            },
        }
    }

    fn dead_man_at(&self) -> Option<Instant> {
        let moving = self.translation.target != 0.0 || self.rotation.target != 0.0;
        self.last_motion.filter(|_| moving).map(|last| last + self.config.dead_man)
    }
}

impl Driver for RflexSim {
    type Command = RflexSimCommand;
    type Event = RflexSimEvent;

    fn handle_command(&mut self, now: Instant, command: RflexSimCommand) {
        self.tick(now);
        match command {
            RflexSimCommand::Bump { panel, corners } => {
                let mask = match self.config.conversion.layout.bumps {
                    Bumps::Panels { .. } => 0x0f,
                    Bumps::Bits { .. } | Bumps::None => 0xff,
                };
                if let Some(slot) = self.bumpers.get_mut(usize::from(panel)) {
                    *slot = corners & mask;
                }
            }
            RflexSimCommand::Joystick { x, y, buttons } => self.joystick = (x, y, buttons),
            RflexSimCommand::Inspect(reply) => {
                let _ = reply.send(self.state());
            }
            RflexSimCommand::Disconnect => self.close = true,
        }
    }

    fn handle_input(&mut self, now: Instant, bytes: &[u8]) {
        self.tick(now);
        self.decoder.push(bytes);
        while let Some(event) = self.decoder.poll() {
            // A command that fails its checksum or layout is ignored, as a base does.
            if let DecoderEvent::Frame { frame, .. } = event
                && let Ok(command) = Command::from_frame(&frame)
            {
                self.handle(now, command);
            }
        }
    }

    fn handle_timeout(&mut self, now: Instant) {
        self.tick(now);
        if let Some((period, mask, due)) = self.odometry
            && now >= due
        {
            self.odometry = Some((period, mask, (due + period).max(now)));
            self.odometry_report(now, mask);
        }
        if let Some((period, due)) = self.dio
            && now >= due
        {
            self.dio = Some((period, (due + period).max(now)));
            let timestamp = self.timestamp(now);
            let addresses = self.config.conversion.layout.bump_addresses();
            let reported = if self.config.body_panels_only { 6 } else { usize::MAX };
            for (address, data) in addresses.zip(self.bumpers.clone()).take(reported) {
                let Ok(address) = u8::try_from(address) else { continue };
                self.send(&Report::Dio { timestamp, address, data });
            }
        }
        if let Some((bank, due)) = self.sonar_next
            && now >= due
        {
            self.sonar_bank(now, bank);
            let banks = self.config.conversion.layout.bank_count().max(1);
            self.sonar_next = Some(((bank + 1) % banks, now + SONAR_BANK_EVERY));
        }
    }

    fn handle_disconnect(&mut self, _reason: &str) {
        // A client left: the base keeps its state for the next one; its
        // dead-man stops it if it was moving.
        self.decoder = FrameDecoder::new();
        self.close = false;
    }

    fn poll_transmit(&mut self, _now: Instant) -> Option<Vec<u8>> {
        self.output.pop_front()
    }

    fn poll_event(&mut self) -> Option<RflexSimEvent> {
        self.events.pop_front()
    }

    fn poll_timeout(&self) -> Option<Instant> {
        [
            self.odometry.map(|(_, _, due)| due),
            self.dio.map(|(_, due)| due),
            self.sonar_next.map(|(_, due)| due),
            self.dead_man_at(),
        ]
        .into_iter()
        .flatten()
        .min()
    }

    fn wants_close(&self) -> bool {
        self.close
    }
}

#[cfg(test)]
mod tests;
