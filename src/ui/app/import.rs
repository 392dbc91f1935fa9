//! The shell's side of File → Import from another tool…: what the import
//! desk finished, added to the document as one undo step.

use super::*;
use crate::interchange::merge;
use crate::project::Edit;
use crate::ui::import::Finished;

impl StudioApp {
    /// Takes what the import desk finished off the frame.
    pub(super) fn poll_import(&mut self, ctx: &egui::Context) {
        for finished in self.desks.import.poll(self.document.project.family) {
            match finished {
                Finished::Failed(error) => {
                    self.say(|language| crate::ui::import::note(&error, crate::ui::import::words(language)), true);
                }
                Finished::MapSaved(path) => {
                    self.say(|language| format!("{} {}", language.strings().msg_saved, path.display()), false);
                }
                Finished::Built(built) => self.add_imported(*built),
                Finished::Exported(path, report) => {
                    let notes = report.approximated.len() + report.dropped.len();
                    let said = report.converted.join("; ");
                    let worded = |language| {
                        let text =
                            format!("{} {}: {said}", crate::ui::import::words(language).exported, path.display());
                        if notes > 0 {
                            format!("{text} ({})", report.lines()[report.converted.len()..].join("; "))
                        } else {
                            text
                        }
                    };
                    self.say(worded, false);
                }
            }
        }
        if self.desks.import.busy() {
            // The worker wakes the window when it is done; this keeps the spinner turning.
            ctx.request_repaint_after(Duration::from_millis(100));
        }
    }

    fn add_imported(&mut self, built: crate::interchange::build::Built) {
        let mut report = built.report;
        let project = &self.document.project;
        let edit = match project.family {
            Family::Servo => {
                let (merged, notes) = merge::servo(&project.servo, &built.project.servo);
                notes.into_iter().for_each(|note| report.approximated(note));
                Edit::ReplaceAll(Box::new(merged))
            }
            Family::Plen2 => match merge::plen2(&project.plen2, &built.project.plen2) {
                Ok((merged, notes)) => {
                    notes.into_iter().for_each(|note| report.approximated(note));
                    Edit::SetPlen2(Box::new(merged))
                }
                Err(error) => {
                    return self
                        .say(|language| crate::ui::import::note(&error, crate::ui::import::words(language)), true);
                }
            },
            // A base, or any other family: the import window offers nothing to create.
            _ => return,
        };
        self.document.apply(edit, None);
        self.document.seal();
        let said = report.converted.join("; ");
        self.say(|language| format!("{}: {said}", crate::ui::import::words(language).imported), false);
        self.desks.import.created(report);
    }
}
