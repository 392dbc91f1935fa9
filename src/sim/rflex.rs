//! The emulated rFLEX base: the server side of `rflex.md` over the same codec.
//! Commanded velocities are integrated with their acceleration limits into
//! odometry reports at the requested period; a ring of sonars measures a
//! simple rectangular room, reported in banks; the battery falls slowly; bump
//! panels can be pressed; the base starts braked and never moves while
//! braked; a dead-man timeout stops it when motion commands stop arriving.
//! Output can be stuffed and salted with line noise (garbage, corrupted and
//! cut frames), each counted, so a test knows where it lands.

use std::collections::VecDeque;
use std::time::{Duration, Instant};

use crossbeam_channel::Sender;

use super::faults::{LineNoise, hits};
use crate::link::Driver;
use crate::protocol::rflex::{
    Axis, B21R, BUMP_PANEL_ADDRESS, Command, Conversion, DecoderEvent, FrameDecoder, Report, SONAR_UNITS_PER_M,
    SonarReading,
};

pub use crate::protocol::rflex::SONARS;
/// Bump panels (DIO addresses 0x40..0x44).
pub const BUMP_PANELS: u8 = 4;
/// The base's radius: it touches a wall when its centre is this close, and
/// its sonars measure from there.
pub const ROBOT_RADIUS_M: f64 = crate::protocol::rflex::B21R_RADIUS_M;
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
    /// The room, metres: the base starts in its middle, facing +x.
    pub room_m: (f64, f64),
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
    /// What each sonar measures now, metres (`None` = no echo), by id.
    pub sonar_m: Vec<Option<f64>>,
}

/// What the owner tells the emulated base.
#[derive(Debug)]
pub enum RflexSimCommand {
    /// Press (`corners` ≠ 0) or release a bump panel (0..4).
    Bump {
        /// The panel.
        panel: u8,
        /// The pressed corners, low 4 bits.
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
    bumpers: [u16; BUMP_PANELS as usize],
    joystick: (i32, i32, u8),
    battery_volts: f64,
    world: (f64, f64, f64),
    frames_sent: u64,
    running_number: u8,
    output: VecDeque<Vec<u8>>,
    events: VecDeque<RflexSimEvent>,
    close: bool,
    /// The bump panel pressed against a wall, if any.
    wall_contact: Option<usize>,
}

impl RflexSim {
    /// A base at rest, braked, in the middle of its room.
    pub fn new(config: RflexSimConfig) -> Self {
        let battery_volts = config.battery_volts;
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
            bumpers: [0; BUMP_PANELS as usize],
            joystick: (0, 0, 0),
            battery_volts,
            world: (0.0, 0.0, 0.0),
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

    /// A base that reaches a wall stops there with the panel that hit it pressed
    /// (front when driving forward, back when reversing); moving away releases it.
    fn walls(&mut self, moved_m: f64) {
        let (width, height) = self.config.room_m;
        let (x, y, theta) = self.world;
        let (max_x, max_y) = (width / 2.0 - ROBOT_RADIUS_M, height / 2.0 - ROBOT_RADIUS_M);
        let clamped = (x.clamp(-max_x, max_x), y.clamp(-max_y, max_y));
        let (front, back) = (0usize, 2usize);
        if clamped != (x, y) {
            self.world = (clamped.0, clamped.1, theta);
            self.translation.velocity = 0.0;
            self.translation.target = 0.0;
            let panel = if moved_m >= 0.0 { front } else { back };
            self.bumpers[panel] = 0b0011;
            self.wall_contact = Some(panel);
        } else if let Some(panel) = self.wall_contact.take() {
            // Off the wall again.
            self.bumpers[panel] = 0;
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

    /// The range the sonar `id` measures to the room's walls, in sonar units,
    /// from the ring on the body's edge where the transducers sit.
    fn sonar_range(&self, id: u8) -> u16 {
        let (x, y, theta) = self.world;
        let (width, height) = self.config.room_m;
        let angle = theta + crate::protocol::rflex::sonar_bearing_rad(id);
        let (dx, dy) = (angle.cos(), angle.sin());
        let mut distance = f64::INFINITY;
        for (d, position, half) in [(dx, x, width / 2.0), (dy, y, height / 2.0)] {
            if d > 1e-9 {
                distance = distance.min((half - position) / d);
            } else if d < -1e-9 {
                distance = distance.min((-half - position) / d);
            }
        }
        let units = ((distance - ROBOT_RADIUS_M).max(0.0) * SONAR_UNITS_PER_M).round();
        // Saturates at the field's maximum: beyond 3000 means no echo anyway.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let range = units.min(f64::from(u16::MAX)) as u16;
        range
    }

    fn sonar_bank(&mut self, now: Instant, bank: u8) {
        let first = bank * 16;
        let last = (first + 16).min(SONARS);
        let readings =
            (first..last).map(|sonar_id| SonarReading { sonar_id, range: self.sonar_range(sonar_id) }).collect();
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
            sonar_m: (0..SONARS).map(|id| crate::protocol::rflex::sonar_metres(self.sonar_range(id))).collect(),
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
                if let Some(slot) = self.bumpers.get_mut(usize::from(panel)) {
                    *slot = corners & 0x0f;
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
            for panel in 0..BUMP_PANELS {
                let data = self.bumpers[usize::from(panel)];
                self.send(&Report::Dio { timestamp, address: BUMP_PANEL_ADDRESS + panel, data });
            }
        }
        if let Some((bank, due)) = self.sonar_next
            && now >= due
        {
            self.sonar_bank(now, bank);
            let banks = SONARS.div_ceil(16);
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
mod tests {
    use super::*;

    fn sim() -> (RflexSim, Instant) {
        let mut sim = RflexSim::new(RflexSimConfig::default());
        let t0 = Instant::now();
        sim.tick(t0);
        (sim, t0)
    }

    #[test]
    fn a_braked_base_does_not_move_and_a_released_one_ramps_at_its_acceleration() {
        let (mut sim, t0) = sim();
        let [forward, turn] = B21R.drive(0.5, 0.0, 0.5);
        sim.handle(t0, forward.clone());
        sim.handle(t0, turn.clone());
        sim.tick(t0 + Duration::from_millis(400));
        assert_eq!(sim.state().distance_m, 0.0, "braked");
        sim.handle(t0, Command::BrakeRelease);
        let t1 = t0 + Duration::from_millis(400);
        sim.handle(t1, forward);
        sim.handle(t1, turn);
        sim.tick(t1 + Duration::from_millis(400));
        let state = sim.state();
        assert!((state.speed_m_per_s - 0.2).abs() < 1e-3, "{state:?}");
        assert!((state.distance_m - 0.04).abs() < 1e-3, "½·a·t² = 0.04 m: {state:?}");
    }

    #[test]
    fn the_dead_man_stops_a_base_whose_commands_stop() {
        let (mut sim, t0) = sim();
        sim.handle(t0, Command::BrakeRelease);
        let [forward, _] = B21R.drive(0.5, 0.0, 0.5);
        sim.handle(t0, forward);
        assert_eq!(sim.poll_timeout(), Some(t0 + Duration::from_millis(500)));
        sim.handle_timeout(t0 + Duration::from_millis(500));
        assert!(sim.events.contains(&RflexSimEvent::DeadManStop));
        sim.tick(t0 + Duration::from_secs(2));
        assert_eq!(sim.state().speed_m_per_s, 0.0);
    }

    #[test]
    fn a_wall_stops_the_base_and_presses_its_front_panel() {
        let (mut sim, t0) = sim();
        sim.handle(t0, Command::BrakeRelease);
        let mut t = t0;
        for _ in 0..100 {
            // Keep the dead-man fed: 1 m/s straight at the wall 2.1 m ahead.
            sim.handle(t, B21R.drive(1.0, 0.0, 5.0)[0].clone());
            t += Duration::from_millis(100);
            sim.tick(t);
        }
        let state = sim.state();
        assert!((state.x_m - (2.1 - ROBOT_RADIUS_M)).abs() < 1e-9, "{state:?}");
        assert_eq!(state.speed_m_per_s, 0.0);
        assert_eq!(sim.bumpers[0], 0b0011, "the front panel is pressed");
        // Backing away releases it.
        sim.handle(t, B21R.drive(-0.5, 0.0, 5.0)[0].clone());
        sim.tick(t + Duration::from_millis(300));
        assert_eq!(sim.bumpers[0], 0);
    }

    #[test]
    fn sonars_measure_the_room_from_the_ring() {
        let (sim, _) = sim();
        // Facing +x in a 4.2 × 2.8 m room, transducers 0.26 m out from the middle:
        // 2.1 − 0.26 = 1.84 m ahead (2715.8 units), 1.4 − 0.26 = 1.14 m to the left (1682.6).
        assert_eq!(sim.sonar_range(0), 2716);
        assert_eq!(sim.sonar_range(6), 1683);
        // Toward a corner (45°): 1.4 / sin 45° = 1.980 m to the long wall, less 0.26 m.
        assert_eq!(sim.sonar_range(3), 2539);
        // Toward the corner itself (30°): 2.1 / cos 30° − 0.26 = 2.165 m, past the 2.03 m limit.
        assert!(sim.sonar_range(2) > crate::protocol::rflex::SONAR_NO_ECHO_ABOVE);
    }
}
