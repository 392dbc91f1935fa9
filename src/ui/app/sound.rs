//! The shell's side of the sound track: kept in step with the project
//! every frame, and its actions applied.

use super::*;
use crate::ui::sound::SoundAction;

impl StudioApp {
    /// Reads the project's sound when it names another file, takes in a
    /// finished reading, and says what the sound has to say (once).
    pub(super) fn keep_sound(&mut self) {
        let folder = self.document.path.as_deref().and_then(std::path::Path::parent).map(std::path::Path::to_path_buf);
        // Play on board waits the link's delay: its time on the line, and the latency the doctor measured.
        self.desks.sound.set_link_latency(self.measured_latency());
        let edit = self.desks.sound.sync(&self.document.project, folder.as_deref(), &self.window.waker);
        if let Some((edit, coalesce)) = edit {
            self.document.apply(edit, Some(coalesce));
            self.document.seal();
        }
        self.say_sound();
    }

    /// Applies a sound action.
    pub(super) fn apply_sound(&mut self, action: SoundAction) {
        let folder = self.document.path.as_deref().and_then(std::path::Path::parent).map(std::path::Path::to_path_buf);
        if let Some((edit, coalesce)) = self.desks.sound.apply(action, &self.document.project, folder.as_deref()) {
            self.document.apply(edit, Some(coalesce));
        }
        self.say_sound();
    }

    fn say_sound(&mut self) {
        if let Some(said) = self.desks.sound.take_said() {
            use crate::ui::sound::Said;
            let worded = |language| {
                let words = crate::ui::sound::lane::words(language);
                match &said {
                    Said::NoOutput(why) => format!("{} ({why})", words.no_output),
                    // Said once: which server, how long, and that the motion plays on.
                    Said::Stalled { server, after_s } => {
                        let server = server.clone().unwrap_or_else(|| words.the_server.to_string());
                        crate::say!(language, "lane.stalled", server, after_s)
                    }
                    Said::Line(line) => line.clone(),
                }
            };
            self.say(worded, false);
        }
    }
}
