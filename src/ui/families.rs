//! The families the editor knows, each with its side of the editor
//! ([`FamilyUi`]): **this file lists them** ([`every_family`]), so a reader
//! finds them in one place (as rerun lists its views); adding a family is a
//! folder of its own and a line here. The shell reaches a family through
//! this list only; tests and a family's own code reach their concrete type
//! with [`Families::of`]. A family handed an action or a notice of another
//! family's type says so loudly (`board_link::misrouted`).

use std::any::Any;

use crate::project::Family;
use crate::ui::family::FamilyUi;

/// Each family's side of the editor, in menu order.
pub struct Families(Vec<Box<dyn FamilyUi>>);

/// Every family's side of the editor as it starts: the one list of them
/// (the test-only echo board last).
fn every_family() -> Vec<Box<dyn FamilyUi>> {
    #[cfg_attr(not(test), allow(unused_mut))]
    let mut families: Vec<Box<dyn FamilyUi>> = vec![
        Box::<crate::ui::servo::ServoUi>::default(),
        Box::<crate::ui::plen2::Plen2Ui>::default(),
        Box::<crate::ui::rflex::RflexUi>::default(),
        Box::<crate::ui::dynamixel::DynamixelUi>::default(),
    ];
    #[cfg(test)]
    families.push(Box::<crate::ui::echo::EchoUi>::default());
    families
}

impl Default for Families {
    fn default() -> Self {
        let mut uis = every_family();
        // In menu order, as the families are ranked.
        uis.sort_by_key(|family_ui| Family::all().iter().position(|family| *family == family_ui.family()));
        Self(uis)
    }
}

impl std::fmt::Debug for Families {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list().entries(self.0.iter().map(|family_ui| family_ui.family())).finish()
    }
}

impl Families {
    /// Where `family` is in the list. Every family of [`Family::all`] has a
    /// side (a test holds it), and no other can be opened: one asked for all
    /// the same is a bug, which panics in debug builds and tests (as a
    /// misrouted action does) and in a release shows the first side rather
    /// than end the session with the user's work.
    fn place(&self, family: Family) -> usize {
        let place = self.0.iter().position(|family_ui| family_ui.family() == family);
        debug_assert!(place.is_some(), "no side of the editor for the {}", family.name());
        place.unwrap_or_default()
    }

    /// The side of the editor of `family`.
    pub fn get(&self, family: Family) -> &dyn FamilyUi {
        &*self.0[self.place(family)]
    }

    /// The side of the editor of `family`, to change.
    pub fn get_mut(&mut self, family: Family) -> &mut dyn FamilyUi {
        let place = self.place(family);
        &mut *self.0[place]
    }

    /// Every family's side of the editor, to change, in menu order.
    pub fn iter_mut(&mut self) -> impl Iterator<Item = &mut dyn FamilyUi> {
        self.0.iter_mut().map(|family_ui| &mut **family_ui as &mut dyn FamilyUi)
    }

    /// The family whose side of the editor is a `T`.
    pub fn of<T: FamilyUi>(&self) -> Option<&T> {
        self.0.iter().find_map(|family_ui| {
            let family_ui: &dyn Any = &**family_ui;
            family_ui.downcast_ref()
        })
    }

    /// The family whose side of the editor is a `T`, to change.
    pub fn of_mut<T: FamilyUi>(&mut self) -> Option<&mut T> {
        self.0.iter_mut().find_map(|family_ui| {
            let family_ui: &mut dyn Any = &mut **family_ui;
            family_ui.downcast_mut()
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::project::Project;

    /// A family with no side of the editor is a bug said at once in tests,
    /// never silently shown as the servo board's side.
    #[test]
    #[should_panic(expected = "no side of the editor for the None board")]
    fn a_family_without_a_side_is_a_bug_not_the_servo_board() {
        let _ = Families::default().get(Family::named("none", "None board"));
    }

    #[test]
    fn each_family_has_its_own_side_in_menu_order() {
        let families = Families::default();
        let listed: Vec<Family> = families.0.iter().map(|family_ui| family_ui.family()).collect();
        assert_eq!(listed, Family::all(), "one side per family, in menu order");
        for &family in Family::all() {
            assert_eq!(families.get(family).family(), family);
        }
        let servo = families.of::<crate::ui::servo::ServoUi>();
        assert!(servo.is_some() && families.of::<crate::ui::rflex::RflexUi>().is_some());
    }

    /// The sound's follow asks the family for its axes and its motion: a
    /// servo board's servos (a macro of steps), a PLEN2's joints (motions in
    /// slots), and a base, which has none, offers no follower.
    #[test]
    fn the_sounds_follow_asks_the_family() {
        use crate::project::Servo;
        use crate::ui::sound::follow::{Follower, Target, words};
        let families = Families::default();
        assert!(families.get(Family::Rflex).sound_follower().is_none(), "a base has no axis to follow");
        let joints = families.get(Family::Plen2).sound_follower().unwrap();
        assert_eq!(joints.axes(&Project::empty(Family::Plen2)).len(), 18, "every PLEN2 joint");
        let mut project = Project::empty(Family::Servo);
        project.servo.servos.push(Servo::new(7, "jaw 下巴"));
        let servos = families.get(Family::Servo).sound_follower().unwrap();
        assert_eq!(servos.axes(&project), vec![(7, "7 jaw 下巴".to_string())]);
        let open: Vec<f64> = (0..1_000).map(|ms| f64::from(ms / 200 % 2)).collect();
        let follower = Follower { closed_deg: 0.0, open_deg: 30.0, tolerance_deg: 1.0 };
        let words = words(crate::ui::i18n::Language::English);
        let (edits, said) = servos.make(&project, 7, &open, (follower, Target::FreeSlots), words).unwrap();
        assert!(matches!(edits.last(), Some(crate::project::Edit::AddMacro(_))), "a macro runs the steps");
        let said = said.in_(crate::ui::i18n::Language::English);
        assert!(said.contains("steps, run by macro"), "{said}");
        // One step is said as one, in every language's own way.
        let one = crate::say!(crate::ui::i18n::Language::English, "follow.made_steps", count = 1, macro_id = 4);
        assert_eq!(one, "1 step, run by macro 4");
        let ja = crate::say!(crate::ui::i18n::Language::Japanese, "follow.made_steps", count = 1, macro_id = 4);
        assert_eq!(ja, "1 ステップ、マクロで実行 4");
        let (edits, _) =
            joints.make(&Project::empty(Family::Plen2), 0, &open, (follower, Target::FreeSlots), words).unwrap();
        assert!(matches!(edits[..], [crate::project::Edit::SetPlen2(_)]), "the motions go into the PLEN2 section");
    }

    /// The shell routes an action to its owner; one that reached another
    /// family (a routing bug) is a panic in tests, never dropped in silence.
    #[test]
    #[should_panic(expected = "the PLEN2 family was handed an action that is not its own")]
    fn an_action_of_another_family_is_a_loud_error() {
        let mut app = crate::ui::StudioApp::new(Project::empty(Family::Plen2), None, crate::link::no_waker());
        let (mut shell, families) = app.split();
        let action = crate::ui::servo::ServoAction::SetPose { servo_id: 1, degree: 0 };
        families.get_mut(Family::Plen2).act(&mut shell, Box::new(action));
    }
}
