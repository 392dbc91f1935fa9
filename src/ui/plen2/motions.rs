//! PLEN2 motions: the list by slot, and the editor of the selected one — name,
//! slot, loop and jump, the frames table (transition, copy / paste, mirror
//! left↔right, move, remove, play from here), the selected frame's 18 values
//! relative to home, a timeline and an angle plot.

use super::Plen2BoardLink;
use super::preview::Preview;
use crate::authoring::bake::{self, Baked, DEFAULT_TOLERANCE_TENTHS};
use crate::project::plen2::{Frame, Joint, LoopRange, Motion, Plen2Project, Pose};
use crate::project::plen2::{MAX_TRANSITION_MS, MIN_TRANSITION_MS, SLOTS};
use crate::project::{Edit, Location, Problem};
use crate::ui::action::{Action, Export, FileRequest};
use crate::ui::graph::{Channel, Curves, Graph, SoundMarks};
use crate::ui::i18n::Strings;
use crate::ui::layout::{self, Layout, Part};
use crate::ui::plen2::action::Plen2Action;
use crate::ui::plen2::captions::Plen2Words;
use crate::ui::rows;
use crate::ui::shell::ShellView;

/// A motion's channels and its frames' lane, as the graph draws them.
type GraphCurves = (Vec<Channel>, Vec<(f64, f64, String)>);

/// The panel's own state: the selected motion and frame, the copied frame.
#[derive(Debug, Default)]
pub struct MotionsPanel {
    selected: usize,
    frame: usize,
    clipboard: Option<Frame>,
    /// Each slot's problems, for the document revision in `flagged_at`.
    flagged: std::collections::BTreeMap<u8, Vec<Problem>>,
    flagged_at: Option<u64>,
    /// The selected motion's joints as the graph draws them, for (revision, motion index).
    curves: Option<((u64, usize), GraphCurves)>,
    /// The graph pane's own state.
    graph: Graph,
    /// The selected motion as the robot stores it, for (revision, motion index).
    baked: Option<((u64, usize), Baked)>,
    /// The frames a retime applies to: first and last, from 0 (all, unless set).
    retime_span: Option<(usize, usize)>,
    /// The sound's onsets on the motion's time, ms (a dragged retime snaps to them).
    onsets_ms: Vec<f64>,
}

fn edit(project: &Plen2Project, change: impl FnOnce(&mut Plen2Project), key: Option<String>) -> Action {
    let mut changed = project.clone();
    change(&mut changed);
    Action::Edit { edit: Edit::SetPlen2(Box::new(changed)), coalesce: key }
}

impl MotionsPanel {
    /// The selected frame, from 0.
    pub fn selected_frame(&self) -> usize {
        self.frame
    }

    /// The selected motion's slot, if any.
    pub fn selected_slot(&self, project: &Plen2Project) -> Option<u8> {
        project.motions.get(self.selected).map(|m| m.slot)
    }

    /// Draws the panel: the motions beside the selected one's editor, its
    /// frames filling the height, the frame's values and plot under them.
    pub fn ui(
        &mut self,
        ui: &mut egui::Ui,
        (view, problems): (&ShellView<'_>, &[Problem]),
        (layout, preview, pose): (&mut Layout, &mut Preview, &[i16; 18]),
        actions: &mut Vec<Action>,
    ) {
        let (project, revision, words) = (&view.project.plen2, view.revision, view.language.strings());
        let connected = view.link.is_some_and(|link| link.plen2().is_some());
        self.onsets_ms = view.sound.onsets_ms();
        if self.flagged_at != Some(revision) {
            self.flagged.clear();
            for problem in problems {
                if let Location::Motion { slot, .. } | Location::Frame { slot, .. } = &problem.location {
                    self.flagged.entry(*slot).or_default().push(problem.clone());
                }
            }
            self.flagged_at = Some(revision);
        }
        ui.horizontal(|ui| {
            ui.heading(words.motions);
            if ui.button(words.plen2().add_motion).clicked() {
                let slot = (0..SLOTS).find(|slot| !project.motions.iter().any(|m| m.slot == *slot)).unwrap_or(0);
                let motion = Motion {
                    slot,
                    name: format!("Motion {slot}"),
                    frames: vec![Frame::new(500, Pose::default())],
                    loop_range: None,
                    jump_slot: None,
                };
                actions.push(edit(project, |p| p.motions.push(motion), None));
                self.selected = project.motions.len();
                self.frame = 0;
            }
        });
        if project.motions.is_empty() {
            return;
        }
        self.selected = self.selected.min(project.motions.len() - 1);
        // What the list needs, apart from the editor's state (at most 90 slots).
        let flagged: std::collections::BTreeSet<u8> = self.flagged.keys().copied().collect();
        let selected = self.selected;
        let mut picked = None;
        let titles = (Some(words.plen2().frame_and_plot), crate::ui::graph::words(words.lang).title);
        let view_open = layout.view_open;
        layout::list_editor_and_graph(ui, "plen2-motions", layout, titles, |ui, part| match part {
            Part::List => rows::names(ui, "plen2-motion-list", project.motions.len(), |ui, index| {
                let motion = &project.motions[index];
                let mark = if flagged.contains(&motion.slot) { "! " } else { "" };
                let text = format!("{mark}{:>2} {}", motion.slot, motion.name);
                if ui.selectable_label(index == selected, text).clicked() {
                    picked = Some(index);
                }
            }),
            Part::Editor => self.editor(ui, project, connected, words, actions),
            Part::Lower => self.lower(ui, project, words, actions),
            // The preview's time cursor, drawn on the graph too (while the preview is open).
            Part::Graph => {
                let cursor = view_open.then_some(preview.transport.t_ms);
                let onsets = std::mem::take(&mut self.onsets_ms);
                self.graph(ui, (project, cursor, (&onsets, view.sound.strip())), words, actions);
                self.onsets_ms = onsets;
            }
            Part::View => {
                let motion = &project.motions[self.selected];
                preview.motion(ui, (project, revision), (motion.slot, self.frame), pose, (view, actions));
            }
        });
        if let Some(index) = picked {
            self.selected = index;
            self.frame = 0;
        }
    }

    /// The selected frame's values under the frames' timeline.
    fn lower(&mut self, ui: &mut egui::Ui, project: &Plen2Project, words: &Strings, actions: &mut Vec<Action>) {
        timeline(ui, (project, self.selected), self.frame, words);
        egui::ScrollArea::vertical().id_salt("plen2-frame-values-scroll").show(ui, |ui| {
            self.frame_values(ui, project, words, actions);
        });
    }

    /// The graph pane: every joint's curve, its keys and handles, what the robot plays.
    fn graph(
        &mut self,
        ui: &mut egui::Ui,
        (project, cursor_ms, (onsets_ms, sound)): (&Plen2Project, Option<f64>, SoundMarks<'_>),
        words: &Strings,
        actions: &mut Vec<Action>,
    ) {
        let index = self.selected;
        let motion = &project.motions[index];
        let key = (self.flagged_at.unwrap_or_default(), index);
        if self.curves.as_ref().is_none_or(|(at, _)| *at != key) {
            self.curves = Some((key, super::graph::curves(project, motion)));
        }
        let Some((_, (channels, lane))) = &self.curves else { return };
        let curves = Curves {
            channels,
            lane,
            update_ms: crate::authoring::fitted::PLEN2_UPDATE_MS,
            onsets_ms,
            sound,
            cursor_ms,
            editable: true,
        };
        if let Some(done) = self.graph.show(ui, "plen2-graph", &curves, words.lang) {
            let changed = super::graph::apply(project, motion, &done);
            actions.push(edit(project, |p| p.motions[index] = changed, None));
        }
    }

    fn editor(
        &mut self,
        ui: &mut egui::Ui,
        project: &Plen2Project,
        connected: bool,
        words: &Strings,
        actions: &mut Vec<Action>,
    ) {
        let index = self.selected;
        let motion = &project.motions[index];
        ui.horizontal(|ui| motion_row(ui, (project, index), connected, words, actions));
        ui.horizontal(|ui| loop_and_jump_row(ui, (project, index), words, actions));
        for problem in self.flagged.get(&motion.slot).map_or(&[][..], Vec::as_slice) {
            let color = match problem.severity {
                crate::project::Severity::Error => ui.visuals().error_fg_color,
                crate::project::Severity::Warning => ui.visuals().warn_fg_color,
            };
            ui.colored_label(
                color,
                format!("{}: {}", words.lang.location(&problem.location), words.lang.problem(&problem.kind)),
            );
        }
        self.budget(ui, motion, words);
        self.frames_table(ui, project, connected, words, actions);
    }

    /// What the curves cost on the robot: its frames of 20, and how far it strays.
    fn budget(&mut self, ui: &mut egui::Ui, motion: &Motion, words: &Strings) {
        if !bake::has_curves(motion) {
            return;
        }
        let key = (self.flagged_at.unwrap_or_default(), self.selected);
        if self.baked.as_ref().is_none_or(|(at, _)| *at != key) {
            self.baked = Some((key, bake::bake_plen2(motion, DEFAULT_TOLERANCE_TENTHS)));
        }
        let Some((_, baked)) = &self.baked else { return };
        let used = baked.motion.frames.len();
        let captions = words.plen2();
        let text = format!(
            "{}: {used} {} · {} {:.1}°",
            captions.on_robot,
            captions.frames_of_20,
            captions.largest_deviation,
            baked.max_error_tenths / 10.0
        );
        // Frame counts of at most 20.
        #[allow(clippy::cast_precision_loss)]
        let fill = used as f32 / 20.0;
        ui.add(egui::ProgressBar::new(fill.min(1.0)).text(text).desired_width(ui.available_width().min(460.0)));
        if baked.widened(DEFAULT_TOLERANCE_TENTHS) {
            ui.colored_label(
                ui.visuals().warn_fg_color,
                format!("{} → {:.1}°", captions.tolerance_widened, baked.tolerance_tenths / 10.0),
            );
        }
    }

    fn frames_table(
        &mut self,
        ui: &mut egui::Ui,
        project: &Plen2Project,
        connected: bool,
        words: &Strings,
        actions: &mut Vec<Action>,
    ) {
        let index = self.selected;
        let motion = &project.motions[index];
        self.frame = self.frame.min(motion.frames.len().saturating_sub(1));
        ui.label(format!("{} ({})", words.plen2().frames, motion.frames.len()));
        self.retime_row(ui, project, words, actions);
        let mut selected = self.frame;
        let clipboard = &mut self.clipboard;
        let height = ui.available_height();
        rows::grid(ui, "plen2-frames", motion.frames.len(), height, |ui, f| {
            let frame = &motion.frames[f];
            if ui.selectable_label(f == selected, format!("#{f}")).clicked() {
                selected = f;
            }
            let mut transition = frame.transition_ms;
            let drag = egui::DragValue::new(&mut transition)
                .clamp_existing_to_range(false)
                .range(MIN_TRANSITION_MS..=MAX_TRANSITION_MS)
                .suffix(" ms");
            if ui.add(drag).changed() {
                actions.push(edit(
                    project,
                    |p| p.motions[index].frames[f].transition_ms = transition,
                    Some(format!("plen2 {index} frame {f} transition")),
                ));
            }
            let mut easing = frame.easing;
            rows::curve(ui, ("plen2-curve", f), &mut easing, words.plen2().curves, words.plen2().curve_hint);
            if easing != frame.easing {
                actions.push(edit(project, |p| p.motions[index].frames[f].easing = easing, None));
            }
            if ui.small_button(words.copy_frame).clicked() {
                *clipboard = Some(*frame);
            }
            if ui
                .add_enabled(
                    clipboard.is_some() && motion.frames.len() < 20,
                    egui::Button::new(words.plen2().paste).small(),
                )
                .clicked()
                && let Some(copied) = *clipboard
            {
                actions.push(edit(project, |p| p.motions[index].frames.insert(f + 1, copied), None));
            }
            if ui.small_button(words.plen2().mirror).clicked() {
                let mirrored = frame.values_tenths_deg.mirrored();
                actions.push(edit(project, |p| p.motions[index].frames[f].values_tenths_deg = mirrored, None));
            }
            if ui.add_enabled(f > 0, egui::Button::new("↑").small()).clicked() {
                actions.push(edit(project, |p| p.motions[index].frames.swap(f, f - 1), None));
                selected = f - 1;
            }
            if ui.add_enabled(f + 1 < motion.frames.len(), egui::Button::new("↓").small()).clicked() {
                actions.push(edit(project, |p| p.motions[index].frames.swap(f, f + 1), None));
                selected = f + 1;
            }
            if ui.add_enabled(motion.frames.len() > 1, egui::Button::new("×").small()).clicked() {
                actions.push(edit(
                    project,
                    |p| {
                        p.motions[index].frames.remove(f);
                    },
                    None,
                ));
            }
            if ui.add_enabled(connected, egui::Button::new(words.plen2().play_from_here).small()).clicked() {
                actions.push(Action::family(Plen2Action::PlayFrom { slot: motion.slot, frame: f }));
            }
        });
        self.frame = selected;
    }

    /// Retimes frames `#first–#last` (all unless set): ×0.5, ×2 or to a total.
    fn retime_row(&mut self, ui: &mut egui::Ui, project: &Plen2Project, words: &Strings, actions: &mut Vec<Action>) {
        let onsets_ms = &self.onsets_ms;
        let index = self.selected;
        let last = project.motions[index].frames.len().saturating_sub(1);
        let (mut first, mut end) = self.retime_span.unwrap_or((0, last));
        end = end.min(last);
        first = first.min(end);
        let mut factor = None;
        ui.horizontal_wrapped(|ui| {
            let label = ui.label(words.plen2().frames);
            ui.add(egui::DragValue::new(&mut first).range(0..=end).prefix("#")).labelled_by(label.id);
            let label = ui.label(words.plen2().to_frame);
            ui.add(egui::DragValue::new(&mut end).range(first..=last).prefix("#")).labelled_by(label.id);
            let total_ms: f64 =
                project.motions[index].frames[first..=end].iter().map(|frame| f64::from(frame.transition_ms)).sum();
            // The span starts where its first frame does (the motion from 0, as the preview plays it).
            let start_ms: f64 =
                project.motions[index].frames[..first].iter().map(|frame| f64::from(frame.transition_ms)).sum();
            let from_start: Vec<f64> = onsets_ms.iter().map(|t| t - start_ms).filter(|t| *t > 0.0).collect();
            factor = rows::retime(ui, words, total_ms, &from_start);
        });
        self.retime_span = Some((first, end)).filter(|span| *span != (0, last));
        if let Some(asked) = factor {
            actions.push(edit(
                project,
                |p| crate::authoring::retime::scale_frames(&mut p.motions[index].frames[first..=end], asked.factor),
                asked.dragging.then(|| format!("plen2 {index} retime")),
            ));
        }
    }

    fn frame_values(&mut self, ui: &mut egui::Ui, project: &Plen2Project, words: &Strings, actions: &mut Vec<Action>) {
        let index = self.selected;
        let Some(frame) = project.motions[index].frames.get(self.frame) else { return };
        let mut pose = frame.values_tenths_deg;
        let mut changed = false;
        ui.label(format!("#{} — {}", self.frame, words.joints));
        egui::Grid::new("plen2-frame-values").show(ui, |ui| {
            for (column, joint) in Joint::ALL.into_iter().enumerate() {
                let mut value = pose.get(joint);
                let name = ui.label(joint.name());
                let drag = egui::DragValue::new(&mut value).clamp_existing_to_range(false).range(-1800..=1800);
                if ui.add(drag).labelled_by(name.id).changed() {
                    pose.set(joint, value);
                    changed = true;
                }
                if column % 3 == 2 {
                    ui.end_row();
                }
            }
        });
        if changed {
            let f = self.frame;
            actions.push(edit(
                project,
                |p| p.motions[index].frames[f].values_tenths_deg = pose,
                Some(format!("plen2 {index} frame {f} values")),
            ));
        }
    }
}

/// A bar per frame, as long as its transition; when the motion jumps on,
/// the motions it plays into follow on the same strip (fainter, each from a
/// mark), so a chain reads as the one movement the robot plays.
fn timeline(ui: &mut egui::Ui, (project, index): (&Plen2Project, usize), selected: usize, words: &Strings) {
    let motion = &project.motions[index];
    let chain = project.chained(motion);
    let length = |m: &Motion| m.frames.iter().map(|f| f64::from(f.transition_ms)).sum::<f64>();
    let total: f64 = length(motion) + chain.iter().map(|m| length(m)).sum::<f64>();
    let width = ui.available_width().max(100.0);
    let (rect, response) = ui.allocate_exact_size(egui::vec2(width, 18.0), egui::Sense::hover());
    let painter = ui.painter_at(rect);
    let mut x = rect.left();
    for (part, shown) in std::iter::once(motion).chain(chain.iter().copied()).enumerate() {
        if part > 0 {
            painter.vline(x, rect.y_range(), ui.visuals().widgets.active.fg_stroke);
        }
        for (f, frame) in shown.frames.iter().enumerate() {
            #[allow(clippy::cast_possible_truncation)]
            let w = (f64::from(frame.transition_ms) / total.max(1.0) * f64::from(width)) as f32;
            let bar = egui::Rect::from_min_size(egui::pos2(x, rect.top()), egui::vec2((w - 1.0).max(1.0), 16.0));
            let fill = match (part, f == selected) {
                (0, true) => ui.visuals().selection.bg_fill,
                (0, false) => ui.visuals().widgets.inactive.bg_fill,
                _ => ui.visuals().widgets.inactive.bg_fill.gamma_multiply(0.45),
            };
            painter.rect_filled(bar, 2.0, fill);
            x += w;
        }
    }
    if !chain.is_empty() {
        let slots: Vec<String> = chain.iter().map(|m| m.slot.to_string()).collect();
        let said = words
            .plen2()
            .plays_on
            .replace("{slots}", &slots.join(" → "))
            .replace("{total}", &format!("{:.2} s", total / 1000.0));
        response.on_hover_text(&said);
        ui.label(egui::RichText::new(said).weak());
    }
}

/// A motion's slot, name, Play on robot, motion.json… and Remove.
fn motion_row(
    ui: &mut egui::Ui,
    (project, index): (&Plen2Project, usize),
    connected: bool,
    words: &Strings,
    actions: &mut Vec<Action>,
) {
    let motion = &project.motions[index];
    let key = |what: &str| Some(format!("plen2 motion {index} {what}"));
    let label = ui.label(words.slot);
    let mut slot = motion.slot;
    if ui
        .add(egui::DragValue::new(&mut slot).clamp_existing_to_range(false).range(0..=SLOTS - 1))
        .labelled_by(label.id)
        .changed()
    {
        actions.push(edit(project, |p| p.motions[index].slot = slot, key("slot")));
    }
    let label = ui.label(words.name);
    let mut name = motion.name.clone();
    if ui.add(egui::TextEdit::singleline(&mut name).char_limit(20).desired_width(170.0)).labelled_by(label.id).changed()
    {
        actions.push(edit(project, |p| p.motions[index].name = name, key("name")));
    }
    if ui.add_enabled(connected, egui::Button::new(words.plen2().play_on_robot)).on_hover_text("$PM").clicked() {
        actions.push(Action::family(Plen2Action::PlayMotion(motion.slot)));
    }
    // The shell asks where, off the frame; the answer comes back as a save.
    if ui.button("motion.json…").on_hover_text(words.plen2().motion_json_hint).clicked() {
        let name = format!("{:02X}_{}.json", motion.slot, motion.name.replace(' ', "_"));
        let slot = motion.slot;
        let export =
            Export::json(name, "PLEN motion", move |path| Action::family(Plen2Action::SaveMotionJson { slot, path }));
        actions.push(Action::AskFile(FileRequest::Export(export)));
    }
    if ui.button(words.remove).clicked() {
        actions.push(edit(
            project,
            |p| {
                p.motions.remove(index);
            },
            None,
        ));
    }
}

/// A motion's loop (frames and passes) and the slot it jumps to after.
fn loop_and_jump_row(
    ui: &mut egui::Ui,
    (project, index): (&Plen2Project, usize),
    words: &Strings,
    actions: &mut Vec<Action>,
) {
    let motion = &project.motions[index];
    let key = |what: &str| Some(format!("plen2 motion {index} {what}"));
    let frames = u8::try_from(motion.frames.len().saturating_sub(1)).unwrap_or(0);
    let mut looping = motion.loop_range.is_some();
    if ui.checkbox(&mut looping, words.plen2().loop_frames).changed() {
        let range = looping.then_some(LoopRange { begin_frame: 0, end_frame: frames, count: 255 });
        actions.push(edit(project, |p| p.motions[index].loop_range = range, None));
    }
    if let Some(mut range) = motion.loop_range {
        let before = range;
        ui.add(egui::DragValue::new(&mut range.begin_frame).clamp_existing_to_range(false).range(0..=frames));
        ui.label("–");
        ui.add(egui::DragValue::new(&mut range.end_frame).clamp_existing_to_range(false).range(0..=frames));
        ui.label("×");
        ui.add(
            egui::DragValue::new(&mut range.count)
                // Passes: count + 1; 255, and a stored 0 (the robot counts it down to 255), forever.
                .custom_formatter(|n, _| if n >= 255.0 || n <= 0.0 { "∞".into() } else { format!("{}", n + 1.0) }),
        );
        if range != before {
            actions.push(edit(project, |p| p.motions[index].loop_range = Some(range), key("loop")));
        }
    }
    ui.separator();
    let mut jumping = motion.jump_slot.is_some();
    if ui.checkbox(&mut jumping, words.plen2().jump_to).changed() {
        actions.push(edit(project, |p| p.motions[index].jump_slot = jumping.then_some(0), None));
    }
    if let Some(mut jump) = motion.jump_slot
        && ui.add(egui::DragValue::new(&mut jump).clamp_existing_to_range(false).range(0..=SLOTS - 1)).changed()
    {
        actions.push(edit(project, |p| p.motions[index].jump_slot = Some(jump), key("jump")));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mirroring_swaps_the_twins_negated_and_twice_is_the_identity() {
        let mut pose = Pose::default();
        pose.set(Joint::LeftShoulderRoll, 375);
        pose.set(Joint::RightKneePitch, -500);
        let mirrored = pose.mirrored();
        assert_eq!(mirrored.get(Joint::RightShoulderRoll), -375);
        assert_eq!(mirrored.get(Joint::LeftKneePitch), 500);
        assert_eq!(mirrored.get(Joint::LeftShoulderRoll), 0);
        assert_eq!(mirrored.mirrored(), pose);
    }
}
