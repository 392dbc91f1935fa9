//! The action editor: an action's steps as an editable table, as a timeline
//! (a lane per servo, a bar per step from 0 to its interval — all steps start
//! together), and as a plot of each servo's angle over time; play it on the
//! board, or preview it on the sliders without one.

use super::ServoBoardLink;
use super::played::Budget;
use super::preview::{Preview, Timed};
use crate::project::{
    Action as ProjectAction, Edit, Location, Problem, Run, ServoProject, Step, next_free_id, validate_servo,
};
use crate::ui::action::Action;
use crate::ui::derive::Derived;
use crate::ui::graph::{Channel, Curves, Graph, SoundMarks};
use crate::ui::i18n::Strings;
use crate::ui::layout::{self, Layout, Part};
use crate::ui::rows;
use crate::ui::servo::action::ServoAction;
use crate::ui::servo::captions::ServoWords;
use crate::ui::shell::ShellView;

/// Validation and the plot's series, for a document revision and a selected
/// action (computed off the frame path for a large project, `ui::derive`).
#[derive(Debug, Default)]
struct Facts {
    /// The selected action's own problems.
    action_problems: Vec<Problem>,
    /// The selected action's first problem per step (1-based).
    step_problems: std::collections::BTreeMap<usize, Problem>,
    /// The selected action's longest step, ms (the timeline's scale).
    longest_ms: f32,
    /// The selected action's steps as the graph draws them.
    channels: Vec<Channel>,
    /// What the preview plays.
    timed: Timed,
}

impl Facts {
    fn compute(project: &ServoProject, selected: usize, board: &str) -> Self {
        let Some(selected_action) = project.actions.get(selected) else { return Self::default() };
        let (timed, series) = super::played::played(project, Run::Action { action_id: selected_action.id }, board);
        let problems = validate_servo(project);
        let action_id = selected_action.id;
        let mut step_problems = std::collections::BTreeMap::new();
        let mut action_problems = Vec::new();
        for problem in &problems {
            match &problem.location {
                Location::Step { action_id: at, step, .. } if *at == action_id => {
                    step_problems.entry(*step).or_insert_with(|| problem.clone());
                }
                Location::Action { action_id: at, .. } if *at == action_id => action_problems.push(problem.clone()),
                _ => {}
            }
        }
        let bars = timeline_bars(selected_action);
        let longest_ms = bars.iter().map(|(_, _, end)| *end).fold(0.0, f32::max).max(10.0);
        let channels = super::graph::action_curves(project, selected_action, &series, board);
        Self { action_problems, step_problems, longest_ms, channels, timed }
    }
}

/// The editor's own state: which action is open, and what was derived for it.
#[derive(Debug, Default)]
pub struct ActionPanel {
    selected: usize,
    facts: Derived<(u64, usize), Facts>,
    /// What the project's curves cost on the board, for (revision, the board's memory).
    budget: Derived<(u64, Option<i64>), Option<Budget>>,
    /// The graph pane's own state.
    graph: Graph,
}

fn set(index: usize, action: ProjectAction, key: Option<String>) -> Action {
    Action::Edit { edit: Edit::SetAction { index, action }, coalesce: key }
}

impl ActionPanel {
    /// Draws the editor: the list of actions beside the selected one's steps,
    /// its timeline and plot under them (every divider can be dragged).
    pub fn ui(
        &mut self,
        ui: &mut egui::Ui,
        view: &ShellView<'_>,
        (layout, preview): (&mut Layout, &mut Preview),
        actions: &mut Vec<Action>,
    ) {
        let (project, revision, connected) = (&view.project.servo, view.revision, view.link.is_some());
        let words = view.language.strings();
        ui.horizontal(|ui| {
            ui.heading(words.actions);
            if ui.button(words.servo().add_action).clicked() {
                let id = next_free_id(project.actions.iter().map(|a| a.id));
                let action =
                    ProjectAction { id, caption: format!("{} {id}", words.servo().action_word), steps: Vec::new() };
                actions.push(Action::Edit { edit: Edit::AddAction(action), coalesce: None });
                self.selected = project.actions.len();
            }
        });
        if project.actions.is_empty() {
            ui.label(words.servo().no_actions);
            return;
        }
        self.selected = self.selected.min(project.actions.len() - 1);
        let index = self.selected;
        let empty = Facts::default();
        let facts = self
            .facts
            .for_selected(ui.ctx(), crate::ui::derive::with_language(revision, view.language), index, || {
                let project = project.clone();
                let board = words.servo().board_line;
                move || Facts::compute(&project, index, board)
            })
            .unwrap_or(&empty);
        let total_bytes = view
            .link
            .and_then(|link| link.servo())
            .and_then(|servo| servo.memory)
            .map(|(free, total)| i64::from(total.unwrap_or(free)));
        let budget = self
            .budget
            .get(ui.ctx(), (revision, total_bytes), || {
                let project = project.clone();
                move || Budget::of(&project, total_bytes)
            })
            .and_then(|(_, budget)| budget.as_ref());
        let selected = &mut self.selected;
        // The preview's time cursor, drawn on the plot too (while the preview is open).
        let cursor = layout.view_open.then_some(preview.transport.t_ms);
        let mut seek = None;
        let graph = &mut self.graph;
        let titles = (Some(words.servo().timeline_and_plot), crate::ui::graph::words(words.lang).title);
        layout::list_editor_and_graph(ui, "actions", layout, titles, |ui, part| match part {
            Part::List => rows::names(ui, "action-list", project.actions.len(), |ui, index| {
                let action = &project.actions[index];
                if ui.selectable_label(index == *selected, format!("{} {}", action.id, action.caption)).clicked() {
                    *selected = index;
                }
            }),
            Part::Editor => {
                budget_meter(ui, budget, words);
                let onsets = view.sound.onsets_ms();
                seek = Self::editor(ui, project, index, (facts, &onsets), connected, words, actions);
            }
            Part::Lower => timeline(ui, project, &project.actions[index], (facts.longest_ms, cursor)),
            Part::View => preview.timed(ui, project, &facts.timed, (view, actions)),
            Part::Graph => {
                let onsets = view.sound.onsets_ms();
                let sound = (&onsets[..], view.sound.strip());
                graph_pane(ui, graph, (project, index), (&facts.channels, cursor, sound), words.lang, actions);
            }
        });
        if let Some(t_ms) = seek {
            preview.transport.seek(t_ms, ui.input(|input| input.time));
        }
    }

    fn editor(
        ui: &mut egui::Ui,
        project: &ServoProject,
        index: usize,
        (derived, onsets_ms): (&Facts, &[f64]),
        connected: bool,
        words: &Strings,
        actions: &mut Vec<Action>,
    ) -> Option<f64> {
        let action = &project.actions[index];
        header(ui, project, index, connected, words, actions);
        ui.horizontal_wrapped(|ui| {
            // Every step: they all start together, so the action keeps its shape.
            #[allow(clippy::cast_precision_loss)]
            let total_ms = crate::project::action_duration_ms(action) as f64;
            if let Some(asked) = rows::retime(ui, words, total_ms, onsets_ms) {
                let mut retimed = action.clone();
                crate::authoring::retime::scale_steps(&mut retimed.steps, asked.factor);
                actions.push(set(index, retimed, asked.dragging.then(|| format!("action {} retime", action.id))));
            }
        });
        for problem in &derived.action_problems {
            ui.colored_label(ui.visuals().warn_fg_color, words.lang.problem(&problem.kind));
        }
        let seek = steps_table(ui, project, index, derived, words, actions);
        let unused = project.servos.iter().find(|servo| action.steps.iter().all(|step| step.servo_id != servo.id));
        if ui.add_enabled(unused.is_some(), egui::Button::new(words.servo().add_step)).clicked()
            && let Some(servo) = unused
        {
            let mut more = action.clone();
            more.steps.push(Step::new(servo.id, servo.home_deg, 50));
            actions.push(set(index, more, None));
        }
        seek
    }
}

/// The graph pane of the selected action: a drag or a shape is one edit of it.
fn graph_pane(
    ui: &mut egui::Ui,
    graph: &mut Graph,
    (project, index): (&ServoProject, usize),
    (channels, cursor_ms, (onsets_ms, sound)): (&[Channel], Option<f64>, SoundMarks<'_>),
    language: crate::ui::i18n::Language,
    actions: &mut Vec<Action>,
) {
    let update_ms = super::graph::UPDATE_MS;
    let curves = Curves { channels, lane: &[], update_ms, onsets_ms, cursor_ms, editable: true, sound };
    if let Some(done) = graph.show(ui, "action-graph", &curves, language) {
        let changed = super::graph::apply(project, &project.actions[index], &done);
        actions.push(set(index, changed, None));
    }
}

/// An action's caption and its buttons: play on the board, preview, mirror, remove.
fn header(
    ui: &mut egui::Ui,
    project: &ServoProject,
    index: usize,
    connected: bool,
    words: &Strings,
    actions: &mut Vec<Action>,
) {
    let action = &project.actions[index];
    // Buttons wrap under the caption when the pane is narrow, never clipped.
    ui.horizontal_wrapped(|ui| {
        let label = ui.label(format!("{} {}", words.servo().action_word, action.id));
        let mut caption = action.caption.clone();
        if ui.text_edit_singleline(&mut caption).labelled_by(label.id).changed() {
            actions.push(set(
                index,
                ProjectAction { caption, ..action.clone() },
                Some(format!("action {} caption", action.id)),
            ));
        }
        if ui.add_enabled(connected, egui::Button::new(words.servo().play_on_board)).clicked() {
            actions.push(Action::family(ServoAction::PlayAction(action.id)));
        }
        if ui.button(words.preview).clicked() {
            actions.push(Action::family(ServoAction::PreviewAction(action.id)));
        }
        let twins = action.steps.iter().any(|step| project.twin(step.servo_id).is_some());
        if ui
            .add_enabled(twins, egui::Button::new(words.servo().mirror))
            .on_hover_text(words.servo().mirror_hint)
            .clicked()
        {
            let steps = project.mirrored(&action.steps);
            actions.push(set(index, ProjectAction { steps, ..action.clone() }, None));
        }
        if ui.button(words.remove).clicked() {
            actions.push(Action::Edit { edit: Edit::RemoveAction { index }, coalesce: None });
        }
    });
}

/// An action's steps as a table (servo, angle, interval, curve, order, problem);
/// a click on a step's number asks the preview to seek to where it arrives.
fn steps_table(
    ui: &mut egui::Ui,
    project: &ServoProject,
    index: usize,
    derived: &Facts,
    words: &Strings,
    actions: &mut Vec<Action>,
) -> Option<f64> {
    let mut seek = None;
    let action = &project.actions[index];
    let headings = words.headings();
    let heading =
        [headings.step, words.servo().servo_word, headings.angle, headings.interval, words.servo().curve, "", ""];
    // The steps fill the pane but for the "Add step" row under them.
    let height = ui.available_height() - rows::widget_row_height(ui) - 2.0 * ui.spacing().item_spacing.y;
    rows::table(ui, "steps", &heading, action.steps.len(), height, |row, position| {
        step_row(row, position, (project, index, derived), words, actions, &mut seek);
    });
    seek
}

/// One step's row: its number (a click seeks the preview), servo, angle,
/// interval, curve, order buttons and problem.
fn step_row(
    row: &mut egui_extras::TableRow<'_, '_>,
    position: usize,
    (project, index, derived): (&ServoProject, usize, &Facts),
    words: &Strings,
    actions: &mut Vec<Action>,
    seek: &mut Option<f64>,
) {
    let action = &project.actions[index];
    let step = &action.steps[position];
    let with = |changed: Step, key: Option<String>| {
        let mut action = action.clone();
        action.steps[position] = changed;
        set(index, action, key)
    };
    let mut row_id = egui::Id::NULL;
    row.col(|ui| {
        // The step's number: a click shows in the preview where its servo arrives.
        let number = ui.add(egui::Button::new(format!("{}", position + 1)).frame(false));
        row_id = number.id;
        if number.on_hover_text(words.servo().step_seek_hint).clicked() {
            *seek = Some(f64::from(step.interval_10ms.max(0)) * 10.0);
        }
    });
    row.col(|ui| {
        if let Some(servo_id) = servo_cell(ui, project, (step, position), row_id) {
            actions.push(with(Step { servo_id, ..*step }, None));
        }
    });
    row.col(|ui| {
        let (low, high) = project.servo(step.servo_id).map_or((i16::MIN, i16::MAX), |s| (s.min_deg, s.max_deg));
        let mut degree = step.degree;
        let drag = egui::DragValue::new(&mut degree).clamp_existing_to_range(false).range(low..=high).suffix("°");
        if ui.add(drag).labelled_by(row_id).changed() {
            let key = format!("action {} step {position} degree", action.id);
            actions.push(with(Step { degree, ..*step }, Some(key)));
        }
    });
    row.col(|ui| {
        let mut interval = step.interval_10ms;
        let drag =
            egui::DragValue::new(&mut interval).clamp_existing_to_range(false).range(0..=i16::MAX).suffix(" × 10 ms");
        if ui.add(drag).labelled_by(row_id).changed() {
            let key = format!("action {} step {position} interval", action.id);
            actions.push(with(Step { interval_10ms: interval, ..*step }, Some(key)));
        }
    });
    row.col(|ui| {
        let mut easing = step.easing;
        let captions = words.servo();
        rows::curve(ui, ("step-curve", position), &mut easing, captions.curves, captions.curve_hint)
            .labelled_by(row_id);
        if easing != step.easing {
            actions.push(with(Step { easing, ..*step }, None));
        }
    });
    row.col(|ui| {
        if let Some(asked) = rows::reorder_buttons(ui, position, action.steps.len(), words.remove) {
            let mut changed = action.clone();
            asked.apply(&mut changed.steps, position);
            actions.push(set(index, changed, None));
        }
    });
    row.col(|ui| {
        if let Some(problem) = derived.step_problems.get(&(position + 1)) {
            ui.colored_label(ui.visuals().error_fg_color, words.lang.problem(&problem.kind));
        }
    });
}

/// A step's servo, picked from the project's (its caption cut to fit); the one picked when it changes.
fn servo_cell(
    ui: &mut egui::Ui,
    project: &ServoProject,
    (step, position): (&Step, usize),
    row_id: egui::Id,
) -> Option<u8> {
    let servo_text = project
        .servo(step.servo_id)
        .map_or_else(|| format!("{} ?", step.servo_id), |s| format!("{} {}", s.id, s.caption));
    let mut servo_id = step.servo_id;
    let servos = &project.servos;
    // A long caption is cut (its whole text is in the list) so the row fits a narrow pane.
    ui.set_max_width(150.0);
    ui.style_mut().wrap_mode = Some(egui::TextWrapMode::Truncate);
    rows::combo(ui, ("step-servo", position), servo_text, &mut servo_id, servos.len(), |i| {
        (servos[i].id, format!("{} {}", servos[i].id, servos[i].caption))
    })
    .labelled_by(row_id);
    (servo_id != step.servo_id).then_some(servo_id)
}

/// What the project's curves cost on the board: its steps (those for curves)
/// and bytes of the board's memory (when connected), how far the board strays
/// from the curves, and a warning when the tolerance had to widen.
fn budget_meter(ui: &mut egui::Ui, budget: Option<&Budget>, words: &Strings) {
    let Some(budget) = budget else { return };
    let captions = words.servo();
    let baked = &budget.baked;
    let added: usize =
        baked.project.actions.iter().rev().take(baked.added_actions).map(|action| action.steps.len()).sum();
    let bytes = budget.bytes.map_or_else(|| "?".to_string(), |bytes| bytes.to_string());
    let memory = match budget.total_bytes {
        Some(total) => format!("{bytes} {} {total} {}", captions.of_word, captions.bytes_word),
        None => format!("{bytes} {}", captions.bytes_word),
    };
    let text = format!(
        "{}: {} {} ({added} {}) · {memory}",
        captions.on_board,
        baked.steps(),
        captions.steps_word,
        captions.for_curves
    );
    // Byte counts far below 2^24: exact enough for a bar.
    #[allow(clippy::cast_precision_loss)]
    let fill = match (budget.bytes, budget.total_bytes) {
        (Some(bytes), Some(total)) if total > 0 => bytes as f32 / total as f32,
        _ => 0.0,
    };
    ui.horizontal_wrapped(|ui| {
        ui.add(egui::ProgressBar::new(fill.min(1.0)).text(text).desired_width(ui.available_width().min(420.0)));
        ui.label(format!("{} {:.1}°", captions.largest_deviation, baked.max_error_deg));
    });
    if budget.widened() {
        ui.colored_label(
            ui.visuals().warn_fg_color,
            format!("{} → {:.1}°", captions.tolerance_widened, baked.tolerance_deg),
        );
    }
}

/// The timeline's bars: per step, its servo and its span in ms (every step
/// starts at 0: all steps of an action start together).
pub fn timeline_bars(action: &ProjectAction) -> Vec<(u8, f32, f32)> {
    action.steps.iter().map(|step| (step.servo_id, 0.0, f32::from(step.interval_10ms.max(0)) * 10.0)).collect()
}

/// A lane per servo, a bar per step from 0 to its interval; only the lanes in
/// view are drawn.
/// The preview's time cursor (ms), if shown, is a line across the lanes.
fn timeline(
    ui: &mut egui::Ui,
    project: &ServoProject,
    action: &ProjectAction,
    (longest_ms, cursor): (f32, Option<f64>),
) {
    if action.steps.is_empty() {
        return;
    }
    let lane_height = 18.0;
    let label_width = 110.0;
    let width = ui.available_width();
    egui::ScrollArea::vertical()
        .id_salt("timeline")
        .max_height((ui.available_height() * 0.4).max(3.0 * lane_height))
        .auto_shrink([false, true])
        .show_viewport(ui, |ui, viewport| {
            let height = lane_height * action.steps.len() as f32 + 16.0;
            let (rect, _) = ui.allocate_exact_size(egui::vec2(width, height), egui::Sense::hover());
            let painter = ui.painter_at(rect);
            let visuals = ui.visuals();
            let small = egui::TextStyle::Small.resolve(ui.style());
            // Room on the right for the longest bar's label.
            let track = egui::Rect::from_min_max(
                egui::pos2(rect.left() + label_width, rect.top()),
                egui::pos2(rect.right() - 110.0, rect.bottom()),
            );
            let x_of = |ms: f32| track.left() + track.width() * ms / longest_ms;
            // Lane numbers from pixels: small, non-negative (the viewport starts at 0).
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            let (first, last) = (
                (viewport.top() / lane_height).floor().max(0.0) as usize,
                ((viewport.bottom() / lane_height).ceil().max(0.0) as usize + 1).min(action.steps.len()),
            );
            for lane in first..last {
                let step = &action.steps[lane];
                let end_ms = f32::from(step.interval_10ms.max(0)) * 10.0;
                let top = rect.top() + lane as f32 * lane_height;
                let caption = project.servo(step.servo_id).map_or("", |s| s.caption.as_str());
                painter.text(
                    egui::pos2(rect.left(), top + lane_height / 2.0),
                    egui::Align2::LEFT_CENTER,
                    format!("{} {caption}", step.servo_id),
                    small.clone(),
                    visuals.text_color(),
                );
                let bar = egui::Rect::from_min_max(
                    egui::pos2(x_of(0.0), top + 3.0),
                    egui::pos2(x_of(end_ms).max(x_of(0.0) + 2.0), top + lane_height - 3.0),
                );
                painter.rect_filled(bar, 3.0, visuals.selection.bg_fill);
                painter.text(
                    bar.right_center() + egui::vec2(4.0, 0.0),
                    egui::Align2::LEFT_CENTER,
                    format!("{}° · {} ms", step.degree, end_ms),
                    small.clone(),
                    visuals.weak_text_color(),
                );
            }
            if let Some(t_ms) = cursor {
                // A cursor past the longest step stays at its end (the pose holds there).
                #[allow(clippy::cast_possible_truncation)]
                let x = x_of((t_ms as f32).min(longest_ms));
                painter.vline(x, rect.y_range(), egui::Stroke::new(1.5, visuals.strong_text_color()));
            }
            time_axis(
                &painter,
                (x_of(0.0), x_of(longest_ms), rect.bottom() - 8.0),
                longest_ms,
                (&small, visuals.weak_text_color()),
            );
        });
}

/// The timeline's time axis: 0 at the start of the track, the longest step at its end.
fn time_axis(
    painter: &egui::Painter,
    (start_x, end_x, y): (f32, f32, f32),
    longest_ms: f32,
    (font, color): (&egui::FontId, egui::Color32),
) {
    painter.text(egui::pos2(start_x, y), egui::Align2::LEFT_CENTER, "0", font.clone(), color);
    painter.text(egui::pos2(end_x, y), egui::Align2::RIGHT_CENTER, format!("{longest_ms} ms"), font.clone(), color);
}
