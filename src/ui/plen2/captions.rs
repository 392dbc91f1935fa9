//! The PLEN2's own captions, in English and Traditional Chinese: the
//! words only its panels use (the shell's and the shared ones are in `ui::i18n`).
//! A panel holding the interface's [`Strings`] reaches them as `words.plen2()`.

use crate::ui::i18n::Strings;

crate::words! {
    /// The PLEN2's own captions.
    #[derive(Debug)]
    pub struct Plen2Captions in "plen2" {
        /// "Factory joint settings".
        pub factory_reset: &'static str,
        /// "Frames".
        pub frames: &'static str,
        /// "Capture into frame".
        pub capture_frame: &'static str,
        /// "Add motion".
        pub add_motion: &'static str,
        /// "Loop frames".
        pub loop_frames: &'static str,
        /// "Then jump to slot".
        pub jump_to: &'static str,
        /// What a motion that jumps on plays into: `{slots}` and `{total}`.
        pub plays_on: &'static str,
        /// "Paste after".
        pub paste: &'static str,
        /// "Mirror L/R".
        pub mirror: &'static str,
        /// "Play from here".
        pub play_from_here: &'static str,
        /// "Play on robot".
        pub play_on_robot: &'static str,
        /// "Add play list".
        pub add_play_list: &'static str,
        /// "Add motion".
        pub add_entry: &'static str,
        /// "Plays (0 = forever)".
        pub plays: &'static str,
        /// "Read robot".
        pub read_robot: &'static str,
        /// "Upload motions".
        pub upload_motions: &'static str,
        /// "Write joint settings".
        pub write_joints: &'static str,
        /// "Slot map: project / robot".
        pub slot_map: &'static str,
        /// "Joint settings (tenths of a degree; the robot stores them)".
        pub joint_settings: &'static str,
        /// "STOP: the motion stopped and every joint went home".
        pub msg_plen2_stopped: &'static str,
        /// What the pacing modes do (hover text).
        pub pacing_hint: &'static str,
        /// "connected to the demo PLEN2 (emulated, factory-fresh: its 90 slots are empty)".
        pub msg_connected_demo_plen2: &'static str,
        /// "Read the robot; motions it holds:".
        pub robot_read: &'static str,
        /// "Still different after writing again (check the cable and upload again), slots:".
        pub slots_differ: &'static str,
        /// The lower pane of the motion editor: "Frame values".
        pub frame_and_plot: &'static str,
        /// What the motion.json button does.
        pub motion_json_hint: &'static str,
        /// Which motion a PLEN2 motion is previewed after.
        pub played_after: &'static str,
        /// The robot just switched on (its frame buffer all zeros).
        pub power_up: &'static str,
        /// Where a PLEN2 motion starts from.
        pub snap_note: &'static str,
        /// The sliders' pose differs from where the motion starts.
        pub snap_warning: &'static str,
        /// The previewed motion never ends on the robot (plen2.md §6).
        pub motion_never_ends: &'static str,
        /// The previewed motion's first frame lasts 0 cycles: the robot divides by zero.
        pub first_frame_undefined: &'static str,
        /// Each curve's name, in `Easing::ALL` order, then a shaped one's.
        pub curves: [&'static str; 6],
        /// What a curve does to the frames the robot stores (hover text).
        pub curve_hint: &'static str,
        /// The budget meter: "On the robot".
        pub on_robot: &'static str,
        /// "frames of 20".
        pub frames_of_20: &'static str,
        /// "largest deviation from the curves".
        pub largest_deviation: &'static str,
        /// "the tolerance was widened from 1° so the curves fit in 20 frames".
        pub tolerance_widened: &'static str,
        /// What Record does (hover text).
        pub record_hint: &'static str,
        /// The motion has no room.
        pub msg_no_room: &'static str,
        /// Too long for the frames left.
        pub msg_recording_too_long: &'static str,
        /// "frames inserted after frame".
        pub frames_inserted_after: &'static str,
        /// The retimed span's last frame: "to frame".
        pub to_frame: &'static str,
    }
}

/// The PLEN2's captions in the interface's language.
pub trait Plen2Words {
    /// The PLEN2's captions in this language.
    fn plen2(&self) -> &'static Plen2Captions;
}

impl Plen2Words for Strings {
    fn plen2(&self) -> &'static Plen2Captions {
        Plen2Captions::of(self.lang)
    }
}
