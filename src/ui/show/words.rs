//! The show window's words, in each language.

use crate::project::Family;
use crate::ui::i18n::Language;

pub(super) fn family_name(family: Family, words: &ShowWords) -> &'static str {
    words.families.iter().find(|(tag, _)| *tag == family.tag()).map_or_else(|| family.name(), |(_, name)| name)
}

crate::words! {
    /// The show window's words.
    #[derive(Debug)]
    pub struct ShowWords in "show" {
        /// The language these words are in.
        pub lang: Language,
        /// The window's title and the File menu's entry.
        pub title: &'static str,
        /// "Show the open project as a show".
        pub this_project: &'static str,
        /// Column heads.
        pub device: &'static str,
        /// "Family".
        pub family: &'static str,
        /// "Port".
        pub port: &'static str,
        /// "Sound".
        pub sound: &'static str,
        /// "Play on the boards".
        pub play: &'static str,
        /// "Stop all".
        pub stop_all: &'static str,
        /// "macro", "motion", "drive".
        pub macro_word: &'static str,
        /// "motion".
        pub motion_word: &'static str,
        /// "drive".
        pub drive_word: &'static str,
        /// Family names by tag.
        pub families: [(&'static str, &'static str); 3],
        /// "If its link is lost".
        pub if_lost: &'static str,
        /// "Connect the boards" (held while the window is open).
        pub connect_boards: &'static str,
        /// "Disconnect the boards".
        pub disconnect_boards: &'static str,
        /// What connected boards do.
        pub boards_follow: &'static str,
        /// The link column's head.
        pub link: &'static str,
        /// A device being connected.
        pub asking: &'static str,
        /// A device that answered.
        pub answered: &'static str,
        /// A device that did not answer.
        pub silent: &'static str,
        /// A device whose link was lost.
        pub lost: &'static str,
        /// After a lost link: every device was stopped.
        pub all_stopped: &'static str,
        /// Settings → "Remote control…".
        pub remote_menu: &'static str,
        /// The remote control window's title.
        pub remote_title: &'static str,
        /// Its on / off box.
        pub remote_serve: &'static str,
        /// "Listen on".
        pub remote_listen: &'static str,
        /// "OSC port".
        pub remote_osc: &'static str,
        /// "Token file".
        pub remote_token: &'static str,
        /// Queue a play on a busy device, or refuse it.
        pub remote_queue: &'static str,
        /// What it serves, and the token rule.
        pub remote_hint: &'static str,
        /// "listening on".
        pub remote_listening: &'static str,
        /// It stopped because the boards went.
        pub remote_stopped: &'static str,
        /// A base a remote drives.
        pub remote_driven: &'static str,
        /// "play on without it".
        pub play_on: &'static str,
        /// "At".
        pub at: &'static str,
        /// "Cue" (a row's name).
        pub cue: &'static str,
        /// "Starts".
        pub starts: &'static str,
        /// "Remove".
        pub remove: &'static str,
        /// "+ Cue".
        pub add_cue: &'static str,
        /// "Save show…".
        pub save: &'static str,
        /// "+ Device".
        pub add_device: &'static str,
        /// "The open project".
        pub from_open: &'static str,
        /// "A project file…".
        pub from_file: &'static str,
        /// "New" (before a family's name).
        pub new: &'static str,
        /// "Find by id".
        pub find: &'static str,
        /// Said when no USB serial device is attached.
        pub none_attached: &'static str,
        /// "Time shown" (the scrub's caption).
        pub scrub: &'static str,
        /// The stage view's name.
        pub stage: &'static str,
        /// "Heading".
        pub heading: &'static str,
        /// The timeline's name (a click shows that time).
        pub timeline: &'static str,
        /// "Preview".
        pub preview: &'static str,
        /// "Stop preview".
        pub stop_preview: &'static str,
        /// "Record a pass of".
        pub record_pass_of: &'static str,
        /// "● Record pass".
        pub record_pass: &'static str,
        /// "■ Stop pass".
        pub stop_pass: &'static str,
        /// "Undo pass".
        pub undo_pass: &'static str,
        /// "its own cue cuts the passes short at" (a board plays one at a time).
        pub cut_short_at: &'static str,
        /// A remote served beyond this computer: "token needed".
        pub remote_token_needed: &'static str,
        /// A remote served on this computer only: "loopback only, no token".
        pub remote_loopback: &'static str,
        /// "slider" (what moves a pass's axis).
        pub by_slider: &'static str,
        /// Said when no gamepad axis has moved yet.
        pub no_pad_axis: &'static str,
    }
}

/// The words in `language`.
pub fn words(language: Language) -> &'static ShowWords {
    ShowWords::of(language)
}
