//! The macro composer: the command list (run action / delay / run macro, each
//! with ratio and loop), reordering, each command's and the macro's computed
//! duration, a plot of every servo's trajectory over the whole macro, and the
//! validation problems of the macro shown inline.

use super::preview::{Preview, Timed};
use crate::project::{
    Command, Edit, Location, Macro, Problem, Run, ServoProject, Severity, Timing, TimingError, next_free_id,
    validate_servo,
};
use crate::ui::action::Action;
use crate::ui::derive::Derived;
use crate::ui::graph::{Channel, Curves, Graph};
use crate::ui::i18n::Strings;
use crate::ui::i18n::Worded;
use crate::ui::layout::{self, Layout, Part};
use crate::ui::rows;
use crate::ui::servo::action::ServoAction;
use crate::ui::servo::captions::ServoWords;
use crate::ui::shell::ShellView;

/// What the composer derives from the project, for a document revision and a
/// selected macro (validation and timing of a large project take milliseconds:
/// computed off the frame path then, `ui::derive`).
#[derive(Debug, Default)]
struct Facts {
    /// The selected macro's own problems.
    macro_problems: Vec<Problem>,
    /// Macros with a problem (marked in the list).
    flagged: std::collections::BTreeSet<i32>,
    /// The selected macro's first problem per command (1-based).
    command_problems: std::collections::BTreeMap<usize, Problem>,
    command_totals_ms: Vec<Result<i64, TimingError>>,
    /// The macro's total (`None` until computed).
    macro_total_ms: Option<Result<i64, TimingError>>,
    /// Each servo as the macro moves it, for the graph.
    channels: Vec<Channel>,
    /// The commands' lane: each one's start, end and number.
    lane: Vec<(f64, f64, String)>,
    /// What the preview plays.
    timed: Timed,
}

impl Facts {
    fn compute(project: &ServoProject, selected: usize, board: &str) -> Self {
        let Some(item) = project.macros.get(selected) else { return Self::default() };
        let timing = Timing::new(project);
        let (timed, series) = super::played::played(project, Run::Macro { macro_id: item.id }, board);
        let problems = validate_servo(project);
        let mut flagged = std::collections::BTreeSet::new();
        let mut command_problems = std::collections::BTreeMap::new();
        let mut macro_problems = Vec::new();
        for problem in &problems {
            match &problem.location {
                Location::Macro { macro_id, .. } => {
                    flagged.insert(*macro_id);
                    if *macro_id == item.id {
                        macro_problems.push(problem.clone());
                    }
                }
                Location::Command { macro_id, command, .. } => {
                    flagged.insert(*macro_id);
                    if *macro_id == item.id {
                        command_problems.entry(*command).or_insert_with(|| problem.clone());
                    }
                }
                _ => {}
            }
        }
        let command_totals_ms: Vec<Result<i64, TimingError>> =
            item.commands.iter().map(|command| timing.command_total_ms(command)).collect();
        let mut lane = Vec::new();
        let mut at = 0_i64;
        for (number, total) in command_totals_ms.iter().enumerate() {
            let Ok(total) = total else { break };
            // Times of a few hours at most: exact.
            #[allow(clippy::cast_precision_loss)]
            lane.push((at as f64, (at + total) as f64, format!("#{}", number + 1)));
            at += total;
        }
        Self {
            macro_problems,
            flagged,
            command_problems,
            command_totals_ms,
            macro_total_ms: Some(timing.macro_total_ms(item.id)),
            channels: super::graph::played_curves(&series, board),
            lane,
            timed,
        }
    }
}

/// The composer's own state: which macro is open, and what was derived for it.
#[derive(Debug, Default)]
pub struct MacroPanel {
    selected: usize,
    facts: Derived<(u64, usize), Facts>,
    /// The graph pane's own state.
    graph: Graph,
}

fn seconds(ms: i64) -> String {
    format!("{:.2} s", ms as f64 / 1000.0)
}

fn edit(index: usize, item: Macro, key: Option<String>) -> Action {
    Action::Edit { edit: Edit::SetMacro { index, item }, coalesce: key }
}

impl MacroPanel {
    /// Draws the composer.
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
            ui.heading(words.macros);
            if ui.button(words.servo().add_macro).clicked() {
                let id = next_free_id(project.macros.iter().map(|m| m.id));
                actions.push(Action::Edit {
                    edit: Edit::AddMacro(Macro {
                        id,
                        caption: format!("{} {id}", words.servo().macro_word),
                        commands: Vec::new(),
                    }),
                    coalesce: None,
                });
                self.selected = project.macros.len();
            }
        });
        if project.macros.is_empty() {
            ui.label(words.servo().no_macros);
            return;
        }
        self.selected = self.selected.min(project.macros.len() - 1);
        let index = self.selected;
        let empty = Facts::default();
        let derived = self
            .facts
            .for_selected(ui.ctx(), crate::ui::derive::with_language(revision, view.language), index, || {
                let project = project.clone();
                let board = words.servo().board_line;
                move || Facts::compute(&project, index, board)
            })
            .unwrap_or(&empty);
        let selected = &mut self.selected;
        // The preview's time cursor, drawn on the plot too (while the preview is open).
        let cursor = layout.view_open.then_some(preview.transport.t_ms);
        let mut played_from = None;
        let (graph, onsets) = (&mut self.graph, view.sound.onsets_ms());
        let titles = (None, crate::ui::graph::words(words.lang).title);
        layout::list_editor_and_graph(ui, "macros", layout, titles, |ui, part| match part {
            Part::List => rows::names(ui, "macro-list", project.macros.len(), |ui, index| {
                let item = &project.macros[index];
                let flagged = derived.flagged.contains(&item.id);
                let text = format!("{}{} {}", if flagged { "! " } else { "" }, item.id, item.caption);
                if ui.selectable_label(index == *selected, text).clicked() {
                    *selected = index;
                }
            }),
            Part::Editor => played_from = Self::editor(ui, project, index, derived, connected, words, actions),
            Part::Lower => {}
            Part::Graph => {
                let curves = Curves {
                    channels: &derived.channels,
                    lane: &derived.lane,
                    update_ms: super::graph::UPDATE_MS,
                    onsets_ms: &onsets,
                    sound: view.sound.strip(),
                    cursor_ms: cursor,
                    editable: false,
                };
                graph.show(ui, "macro-graph", &curves, words.lang);
            }
            Part::View => preview.timed(ui, project, &derived.timed, (view, actions)),
        });
        // Played from a command: the preview's cursor goes where it starts.
        if let Some(position) = played_from {
            let before: Result<i64, _> = derived.command_totals_ms.iter().take(position).cloned().sum();
            if let Ok(start_ms) = before {
                // Times of a few hours at most: exact.
                #[allow(clippy::cast_precision_loss)]
                preview.transport.seek(start_ms as f64, ui.input(|input| input.time));
            }
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn editor(
        ui: &mut egui::Ui,
        project: &ServoProject,
        index: usize,
        derived: &Facts,
        connected: bool,
        words: &Strings,
        actions: &mut Vec<Action>,
    ) -> Option<usize> {
        let mut played_from = None;
        let item = &project.macros[index];
        // Buttons wrap under the caption when the pane is narrow, never clipped.
        ui.horizontal_wrapped(|ui| macro_header(ui, (item, index), derived, connected, words, actions));
        for problem in &derived.macro_problems {
            ui.colored_label(ui.visuals().warn_fg_color, words.lang.problem(&problem.kind));
        }
        // The commands fill the pane but for their notes and the row of "Add" buttons.
        let notes = derived.command_problems.len();
        let below = notes.min(3) + usize::from(notes > 3) + 1;
        let height = ui.available_height() - rows::table_height(ui, below) - ui.spacing().item_spacing.y;
        rows::grid(ui, "commands", item.commands.len(), height, |ui, position| {
            let command = &item.commands[position];
            let total = derived.command_totals_ms.get(position).copied().unwrap_or(Err(TimingError::ZeroRatio));
            if ui.small_button(words.servo().play_here).on_hover_text(words.servo().play_from_here_hint).clicked() {
                played_from = Some(position);
                actions.push(Action::family(ServoAction::PlayMacroFrom { macro_id: item.id, command: position }));
            }
            Self::command_row(ui, project, total, item, index, position, command, words, actions);
            if let Some(problem) = derived.command_problems.get(&(position + 1)) {
                let color = match problem.severity {
                    Severity::Error => ui.visuals().error_fg_color,
                    Severity::Warning => ui.visuals().warn_fg_color,
                };
                // The row is marked; the note itself is below the table.
                ui.colored_label(color, "!").on_hover_text(words.lang.problem(&problem.kind));
            }
        });
        for (at, problem) in derived.command_problems.iter().take(3) {
            let color = match problem.severity {
                Severity::Error => ui.visuals().error_fg_color,
                Severity::Warning => ui.visuals().warn_fg_color,
            };
            ui.colored_label(color, format!("{at}: {}", words.lang.problem(&problem.kind)));
        }
        if notes > 3 {
            ui.colored_label(ui.visuals().warn_fg_color, format!("… +{}", notes - 3));
        }
        ui.horizontal(|ui| add_buttons(ui, project, (item, index), words, actions));
        played_from
    }

    #[allow(clippy::too_many_arguments)]
    fn command_row(
        ui: &mut egui::Ui,
        project: &ServoProject,
        total_ms: Result<i64, TimingError>,
        item: &Macro,
        index: usize,
        position: usize,
        command: &Command,
        words: &Strings,
        actions: &mut Vec<Action>,
    ) {
        let with = |changed: Command, key: Option<String>| {
            let mut item = item.clone();
            item.commands[position] = changed;
            edit(index, item, key)
        };
        // Drag a row by its number onto another row's number to move it there.
        let handle_id = ui.make_persistent_id(("command-drag", item.id, position));
        let handle = ui.dnd_drag_source(handle_id, position, |ui| ui.label(format!("≡ {}", position + 1)));
        let row = handle.inner;
        if let Some(from) = handle.response.dnd_release_payload::<usize>()
            && *from != position
            && *from < item.commands.len()
        {
            let mut moved = item.clone();
            let command = moved.commands.remove(*from);
            moved.commands.insert(position, command);
            actions.push(edit(index, moved, None));
        }
        let run = run_picker(ui, project, (item, position, command.run), row.id, words);
        if run != command.run {
            let key = matches!(run, Run::Delay { .. }).then(|| format!("macro {} command {position} delay", item.id));
            actions.push(with(Command { run, ..*command }, key));
        }
        let mut ratio = command.ratio_percent;
        if ui.add(egui::DragValue::new(&mut ratio).clamp_existing_to_range(false).range(1..=100).suffix(" %")).changed()
        {
            actions.push(with(
                Command { ratio_percent: ratio, ..*command },
                Some(format!("macro {} command {position} ratio", item.id)),
            ));
        }
        let mut loops = command.loop_count;
        if ui
            .add(egui::DragValue::new(&mut loops).clamp_existing_to_range(false).range(1..=i16::MAX).prefix("× "))
            .changed()
        {
            actions.push(with(
                Command { loop_count: loops, ..*command },
                Some(format!("macro {} command {position} loop", item.id)),
            ));
        }
        match total_ms {
            Ok(total) => ui.monospace(seconds(total)),
            Err(_) => ui.monospace("—"),
        };
        ui.horizontal(|ui| {
            if let Some(asked) = rows::reorder_buttons(ui, position, item.commands.len(), words.remove) {
                let mut changed = item.clone();
                asked.apply(&mut changed.commands, position);
                actions.push(edit(index, changed, None));
            }
        });
    }
}

/// A macro's caption, its total time, Run on board and Remove.
fn macro_header(
    ui: &mut egui::Ui,
    (item, index): (&Macro, usize),
    derived: &Facts,
    connected: bool,
    words: &Strings,
    actions: &mut Vec<Action>,
) {
    let label = ui.label(format!("{} {}", words.servo().macro_word, item.id));
    let mut caption = item.caption.clone();
    if ui.text_edit_singleline(&mut caption).labelled_by(label.id).changed() {
        let key = format!("macro {} caption", item.id);
        actions.push(edit(index, Macro { caption, ..item.clone() }, Some(key)));
    }
    match derived.macro_total_ms {
        Some(Ok(total)) => ui.label(format!("{} {}", words.total, seconds(total))),
        Some(Err(error)) => ui.colored_label(ui.visuals().warn_fg_color, error.worded(words.lang)),
        None => ui.label(format!("{} …", words.total)),
    };
    if ui.add_enabled(connected, egui::Button::new(words.servo().run_on_board)).clicked() {
        actions.push(Action::family(ServoAction::RunMacro(item.id)));
    }
    if ui.button(words.remove).clicked() {
        actions.push(Action::Edit { edit: Edit::RemoveMacro { index }, coalesce: None });
    }
}

/// Add an action, a delay or a macro at the end of a macro.
fn add_buttons(
    ui: &mut egui::Ui,
    project: &ServoProject,
    (item, index): (&Macro, usize),
    words: &Strings,
    actions: &mut Vec<Action>,
) {
    let add = |run: Run| {
        let mut changed = item.clone();
        changed.commands.push(Command::once(run));
        edit(index, changed, None)
    };
    if ui.button(words.servo().add_action_command).clicked() {
        let action_id = project.actions.first().map_or(1, |a| a.id);
        actions.push(add(Run::Action { action_id }));
    }
    if ui.button(words.servo().add_delay).clicked() {
        actions.push(add(Run::Delay { delay_ms: 500 }));
    }
    if ui.button(words.servo().add_macro_command).clicked() {
        let macro_id = project.macros.iter().find(|m| m.id != item.id).map_or(item.id, |m| m.id);
        actions.push(add(Run::Macro { macro_id }));
    }
}

/// What a command runs: its kind and its action, delay or macro; the run as picked.
fn run_picker(
    ui: &mut egui::Ui,
    project: &ServoProject,
    (item, position, run): (&Macro, usize, Run),
    row_id: egui::Id,
    words: &Strings,
) -> Run {
    let mut run = run;
    let kind_label = match run {
        Run::Action { .. } => words.servo().action_word,
        Run::Delay { .. } => words.servo().delay,
        Run::Macro { .. } => words.servo().macro_word,
    };
    egui::ComboBox::from_id_salt(("kind", position))
        .selected_text(kind_label)
        .show_ui(ui, |ui| {
            let first_action = project.actions.first().map_or(1, |a| a.id);
            ui.selectable_value(&mut run, Run::Action { action_id: first_action }, words.servo().action_word);
            ui.selectable_value(&mut run, Run::Delay { delay_ms: 500 }, words.servo().delay);
            ui.selectable_value(&mut run, Run::Macro { macro_id: item.id }, words.servo().macro_word);
        })
        .response
        .labelled_by(row_id);
    match &mut run {
        Run::Action { action_id } => {
            let shown = project
                .action(*action_id)
                .map_or_else(|| format!("{action_id} ?"), |a| format!("{} {}", a.id, a.caption));
            let all = &project.actions;
            rows::combo(ui, ("target", position), shown, action_id, all.len(), |i| {
                (all[i].id, format!("{} {}", all[i].id, all[i].caption))
            })
            .labelled_by(row_id);
        }
        Run::Macro { macro_id } => {
            let shown = project
                .macro_by_id(*macro_id)
                .map_or_else(|| format!("{macro_id} ?"), |m| format!("{} {}", m.id, m.caption));
            let all = &project.macros;
            rows::combo(ui, ("target", position), shown, macro_id, all.len(), |i| {
                (all[i].id, format!("{} {}", all[i].id, all[i].caption))
            })
            .labelled_by(row_id);
        }
        Run::Delay { delay_ms } => {
            ui.add(egui::DragValue::new(delay_ms).clamp_existing_to_range(false).range(0..=i32::MAX).suffix(" ms"));
        }
    }
    run
}
