//! The rFLEX base's own captions, in English and Traditional Chinese: the
//! words only its panels use (the shell's and the shared ones are in `ui::i18n`).
//! A panel holding the interface's [`Strings`] reaches them as `words.rflex()`.

use crate::ui::i18n::Strings;

crate::words! {
    /// The rFLEX base's own captions.
    #[derive(Debug)]
    pub struct RflexCaptions in "rflex" {
        /// "Odometry".
        pub odometry: &'static str,
        /// "Measured".
        pub measured: &'static str,
        /// "Acceleration (m/s²)".
        pub acceleration: &'static str,
        /// "Sonar".
        pub sonar: &'static str,
        /// "Drag in the pad, or hold the arrow keys; release to stop. Space or Esc: STOP.".
        pub pad_hint: &'static str,
        /// "Top speed (m/s)".
        pub max_speed: &'static str,
        /// "Top turn (rad/s)".
        pub max_turn: &'static str,
        /// "Joystick".
        pub joystick_state: &'static str,
        /// "STOP: the base was told to stop at once".
        pub msg_base_stopped: &'static str,
        /// "The base stopped answering while driving; it was sent a stop. Check the cable and its power.".
        pub msg_base_silent: &'static str,
        /// "connected to the demo base (emulated, braked, in a 4.2 × 2.8 m room)".
        pub msg_connected_demo_rflex: &'static str,
        /// The status after the brake was set.
        pub msg_brake_on: &'static str,
        /// The status after the brake was released.
        pub msg_brake_released: &'static str,
        /// What "(+N ?)" after the sonar count means.
        pub sonar_unknown_hint: &'static str,
        /// The rFLEX world view.
        pub world_view: &'static str,
        /// Follow the base in the world view.
        pub follow: &'static str,
        /// Forget the echoes seen.
        pub clear_map: &'static str,
        /// How the world view is moved.
        pub world_hint: &'static str,
        /// The drive pad says the window lacks keyboard focus.
        pub drive_needs_focus: &'static str,
        /// How the gamepad drives.
        pub gamepad_hint: &'static str,
        /// "driving".
        pub pad_driving: &'static str,
        /// "stopped: the dead-man button is not held".
        pub pad_released: &'static str,
        /// "stopped: the stick is centred".
        pub pad_centred: &'static str,
        /// "stopped: the gamepad's events were dropped; press the dead-man again".
        pub pad_dropped: &'static str,
        /// "stopped: let go of the dead-man and press it again to drive".
        pub pad_halted: &'static str,
    }
}

/// The rFLEX base's captions in the interface's language.
pub trait RflexWords {
    /// The rFLEX base's captions in this language.
    fn rflex(&self) -> &'static RflexCaptions;
}

impl RflexWords for Strings {
    fn rflex(&self) -> &'static RflexCaptions {
        RflexCaptions::of(self.lang)
    }
}
