//! Posing a figure by its hands and feet, for any family: the choices (keep
//! an end's turn, symmetric, which foot the figure stands on), the rings to
//! drag, and what a drag solves to. The family gives its chain, limbs, twins
//! and limits ([`Rig`]) and sends the angles that come back; a drag's first
//! frame remembers the pose, so that its release makes one undo step.

use super::{End, Gap, Touch, View};
use crate::figure::ik::{self, Goal, Limb};
use crate::figure::{Chain, Mat3, Placed, Vec3};
use crate::ui::i18n::Language;

/// What a family's figure is posed with.
#[derive(Clone, Copy, Debug)]
pub struct Rig<'a> {
    /// The chain.
    pub chain: &'a Chain,
    /// Its limbs, posed by their ends.
    pub limbs: &'a [Limb],
    /// Each limb's twin on the other side (symmetric posing mirrors it across y = 0).
    pub twins: &'a [Option<usize>],
    /// Every link's limits (radians).
    pub limits: &'a [(f32, f32)],
    /// Millimetres per unit of the chain (for the gap's words).
    pub mm_per_unit: f32,
}

/// Closer than this (mm, degrees) is reached.
const REACHED: (f32, f32) = (0.5, 0.5);

/// The user's choices and the drag under way.
#[derive(Clone, Debug, PartialEq)]
pub struct Posing {
    /// A dragged end keeps the turn it had (a foot stays flat); else only its place is held.
    pub keep_turn: bool,
    /// The dragged limb's twin mirrors it.
    pub symmetric: bool,
    /// The limb the figure stands on (planted where it stands at home); none: the body is fixed.
    pub stand_on: Option<usize>,
    drag: Option<Drag>,
    /// The goal the last drag did not reach.
    gap: Option<Gap>,
}

impl Default for Posing {
    /// A dragged foot stays flat (its place alone would often be reached by
    /// rolling the foot, the knee near straight); nothing mirrored; the body fixed.
    fn default() -> Self {
        Self { keep_turn: true, symmetric: false, stand_on: None, drag: None, gap: None }
    }
}

#[derive(Clone, Debug, PartialEq)]
struct Drag {
    end: usize,
    /// Where the root was when grabbed.
    base: Placed,
    /// The dragged end as it was (its turn is kept).
    start: Placed,
    /// Ends held where they were (the feet, while the pelvis moves).
    held: Vec<(usize, Placed)>,
}

/// What a frame of posing asks for.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Posed {
    /// New angles for every link, to send (live).
    pub angles: Option<Vec<f32>>,
    /// The drag let go: the pose since it began is one undo step.
    pub done: bool,
}

impl Posing {
    /// Where the chain's root is for `angles`: standing on the chosen limb's end
    /// where it stands at home, or fixed.
    pub fn base(&self, rig: &Rig<'_>, angles: &[f32]) -> Placed {
        let Some(limb) = self.stand_on.and_then(|index| rig.limbs.get(index)) else { return Placed::ORIGIN };
        let home = vec![0.0; rig.chain.links.len()];
        let (Some(at_home), Some(now)) = (limb.reach(&rig.chain.pose(&home)), limb.reach(&rig.chain.pose(angles)))
        else {
            return Placed::ORIGIN;
        };
        at_home.then(&Placed::ORIGIN.relative_to(&now))
    }

    /// The rings to drag (each limb's end, then the pelvis when the figure stands on a foot).
    pub fn ends(&self, rig: &Rig<'_>, placed: &[Placed], language: Language) -> Vec<End> {
        let words = words(language);
        let mut ends: Vec<End> = rig
            .limbs
            .iter()
            .enumerate()
            .filter_map(|(index, limb)| {
                let names: Vec<&str> =
                    limb.joints.iter().filter_map(|&link| Some(rig.chain.links.get(link)?.name.as_str())).collect();
                let held = self.stand_on == Some(index);
                let how = if held { words.planted } else { words.drag_end };
                let reading = format!("{}: {}\n{how}", shown(&limb.name, language), names.join(" → "));
                Some(End { at: limb.reach(placed)?.position, reading, held })
            })
            .collect();
        if self.stand_on.is_some()
            && let Some(body) = placed.first()
        {
            ends.push(End { at: body.position, reading: words.pelvis.to_string(), held: false });
        }
        ends
    }

    /// The goal the last drag did not reach, to draw.
    pub fn gap(&self) -> Option<Gap> {
        self.gap.clone()
    }

    /// A frame of a drag on an end: the angles that reach its goal (`angles`
    /// now, `base` where the root is).
    pub fn reach(&mut self, rig: &Rig<'_>, angles: &[f32], base: Placed, touch: &Touch, language: Language) -> Posed {
        let mut posed = Posed::default();
        if let Some((end, goal)) = touch.reached {
            let drag = self.drag.get_or_insert_with(|| grabbed(rig, angles, base, end, self.stand_on));
            let (solved, missed) = if end == rig.limbs.len() {
                pelvis(rig, angles, drag, goal)
            } else {
                limb(rig, angles, drag, goal, (self.keep_turn, self.symmetric))
            };
            self.gap = missed.map(|(from, to)| {
                let mm = (to - from).length() * rig.mm_per_unit;
                Gap { from, to, words: format!("{mm:.1} mm {}", words(language).out_of_reach) }
            });
            if solved.as_deref() != Some(angles) {
                posed.angles = solved;
            }
        }
        if touch.released.is_some() {
            self.drag = None;
            self.gap = None;
            posed.done = true;
        }
        posed
    }

    /// The posing choices, in a row: keep turn, symmetric, stand on, frame all.
    pub fn toolbar(&mut self, ui: &mut egui::Ui, limbs: &[Limb], view: &mut View, language: Language) {
        let words = words(language);
        ui.horizontal_wrapped(|ui| {
            ui.checkbox(&mut self.keep_turn, words.keep_turn).on_hover_text(words.keep_turn_hint);
            ui.checkbox(&mut self.symmetric, words.symmetric).on_hover_text(words.symmetric_hint);
            let label = ui.label(words.stand_on);
            let name = |stand: Option<usize>| {
                stand.and_then(|index| limbs.get(index)).map_or(words.body_fixed, |limb| shown(&limb.name, language))
            };
            egui::ComboBox::from_id_salt("stand-on")
                .selected_text(name(self.stand_on))
                .show_ui(ui, |ui| {
                    ui.selectable_value(&mut self.stand_on, None, words.body_fixed);
                    for index in 0..limbs.len() {
                        ui.selectable_value(&mut self.stand_on, Some(index), name(Some(index)));
                    }
                })
                .response
                .labelled_by(label.id)
                .on_hover_text(words.stand_on_hint);
            if ui.button(words.frame_all).on_hover_text(words.frame_all_hint).clicked() {
                view.frame_all();
            }
        });
    }
}

/// What a drag holds from its first frame.
fn grabbed(rig: &Rig<'_>, angles: &[f32], base: Placed, end: usize, stand_on: Option<usize>) -> Drag {
    let placed = rig.chain.pose_from(base, angles);
    let start = rig.limbs.get(end).and_then(|limb| limb.reach(&placed)).unwrap_or(Placed::ORIGIN);
    // The pelvis holds every foot that touches the ground with the one stood on: both feet.
    let held = if end == rig.limbs.len() {
        let stood = stand_on.and_then(|index| rig.limbs.get(index).map(|limb| (index, limb)));
        let mut held: Vec<(usize, Placed)> =
            stood.and_then(|(index, limb)| Some((index, limb.reach(&placed)?))).into_iter().collect();
        if let Some(twin) = stand_on.and_then(|index| rig.twins.get(index).copied().flatten())
            && let Some(at) = rig.limbs.get(twin).and_then(|limb| limb.reach(&placed))
        {
            held.push((twin, at));
        }
        held
    } else {
        Vec::new()
    };
    let start = if end == rig.limbs.len() { placed.first().copied().unwrap_or(Placed::ORIGIN) } else { start };
    Drag { end, base, start, held }
}

/// A limb's end to `goal` (and its twin to the mirror image): the angles, and the gap if it fell short.
fn limb(
    rig: &Rig<'_>,
    angles: &[f32],
    drag: &Drag,
    goal: Vec3,
    (keep_turn, symmetric): (bool, bool),
) -> (Option<Vec<f32>>, Option<(Vec3, Vec3)>) {
    let Some(limb) = rig.limbs.get(drag.end) else { return (None, None) };
    // A limb of fewer than five joints (an arm) cannot hold a turn as well as a place.
    let goal = if keep_turn && limb.joints.len() >= 5 {
        Goal::Hold(Placed { position: goal, rotation: drag.start.rotation })
    } else {
        Goal::Reach(goal)
    };
    let solved = ik::solve(rig.chain, drag.base, angles, limb, goal, rig.limits);
    let mut out = solved.angles.clone();
    let mut missed = (!solved.reached(REACHED.0 / rig.mm_per_unit, REACHED.1.to_radians()))
        .then(|| (reached_at(rig, drag.base, &out, limb), position(goal)));
    if symmetric && let Some(twin) = rig.twins.get(drag.end).copied().flatten().and_then(|twin| rig.limbs.get(twin)) {
        // Mirrored in the body's frame, across its middle.
        let local = match goal {
            Goal::Reach(at) => {
                Goal::Reach(Placed { position: at, rotation: Mat3::IDENTITY }.relative_to(&drag.base).position)
            }
            Goal::Hold(placed) => Goal::Hold(placed.relative_to(&drag.base)),
        };
        let mirrored = match ik::mirrored(local) {
            Goal::Reach(at) => Goal::Reach(drag.base.then(&Placed { position: at, rotation: Mat3::IDENTITY }).position),
            Goal::Hold(placed) => Goal::Hold(drag.base.then(&placed)),
        };
        let twin_solved = ik::solve(rig.chain, drag.base, &out, twin, mirrored, rig.limits);
        let twin_reached = twin_solved.reached(REACHED.0 / rig.mm_per_unit, REACHED.1.to_radians());
        out = twin_solved.angles;
        if missed.is_none() && !twin_reached {
            missed = Some((reached_at(rig, drag.base, &out, twin), position(mirrored)));
        }
    }
    (Some(out), missed)
}

/// The pelvis to `goal` over the held feet; where the feet cannot hold, it stops where it was.
fn pelvis(rig: &Rig<'_>, angles: &[f32], drag: &Drag, goal: Vec3) -> (Option<Vec<f32>>, Option<(Vec3, Vec3)>) {
    let base = Placed { position: drag.base.position + (goal - drag.start.position), ..drag.base };
    let held: Vec<(&Limb, Placed)> =
        drag.held.iter().filter_map(|(index, at)| Some((rig.limbs.get(*index)?, *at))).collect();
    let kept = ik::keep_planted(rig.chain, base, angles, &held, rig.limits);
    if kept.reached(REACHED.0 / rig.mm_per_unit, REACHED.1.to_radians()) {
        (Some(kept.angles), None)
    } else {
        // The feet would slip: the pose stays, and the gap shows how far the pelvis was pulled.
        let now = rig.chain.pose_from(drag.base, angles).first().map_or(goal, |body| body.position);
        (None, Some((now, goal)))
    }
}

fn reached_at(rig: &Rig<'_>, base: Placed, angles: &[f32], limb: &Limb) -> Vec3 {
    limb.reach(&rig.chain.pose_from(base, angles)).map_or(Vec3::ZERO, |at| at.position)
}

fn position(goal: Goal) -> Vec3 {
    match goal {
        Goal::Reach(at) => at,
        Goal::Hold(placed) => placed.position,
    }
}

crate::words! {
    /// The posing row's words.
    #[derive(Debug)]
    pub struct PosingWords in "posing" {
        /// "Keep turn".
        pub keep_turn: &'static str,
        /// Its hover.
        pub keep_turn_hint: &'static str,
        /// "Symmetric".
        pub symmetric: &'static str,
        /// Its hover.
        pub symmetric_hint: &'static str,
        /// "Stand on".
        pub stand_on: &'static str,
        /// Its hover.
        pub stand_on_hint: &'static str,
        /// "body fixed" (stand on nothing).
        pub body_fixed: &'static str,
        /// "Frame all".
        pub frame_all: &'static str,
        /// Its hover.
        pub frame_all_hint: &'static str,
        /// Hover of an end: how to drag it.
        pub drag_end: &'static str,
        /// Hover of the end stood on.
        pub planted: &'static str,
        /// Hover of the pelvis.
        pub pelvis: &'static str,
        /// After a gap's millimetres: "out of reach".
        pub out_of_reach: &'static str,
        /// The PLEN2's own limbs: left foot, right foot, left hand, right hand.
        pub limbs: [&'static str; 4],
    }
}

/// A limb's name as shown: the PLEN2's own four in the interface's
/// language; a rig's (its servo's caption) as the user wrote it.
pub fn shown(name: &str, language: Language) -> &str {
    let limbs = PosingWords::of(language).limbs;
    ["left foot", "right foot", "left hand", "right hand"]
        .iter()
        .zip(limbs)
        .find(|(english, _)| **english == name)
        .map_or(name, |(_, shown)| shown)
}

/// The posing row's words in `language`.
pub fn words(language: Language) -> &'static PosingWords {
    PosingWords::of(language)
}
