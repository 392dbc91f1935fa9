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
    /// Where `family` is in the list (every family of [`Family::all`] has a
    /// side: a test holds it; any other falls back to the first, the servo board's).
    fn place(&self, family: Family) -> usize {
        self.0.iter().position(|family_ui| family_ui.family() == family).unwrap_or_default()
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

    /// The shell routes an action to its owner; one that reached another
    /// family (a routing bug) is a panic in tests, never dropped in silence.
    #[test]
    #[should_panic(expected = "the PLEN2 family was handed an action that is not its own")]
    fn an_action_of_another_family_is_a_loud_error() {
        let mut app =
            crate::ui::StudioApp::new(crate::project::Project::empty(Family::Plen2), None, crate::link::no_waker());
        let (mut shell, families) = app.split();
        let action = crate::ui::servo::ServoAction::SetPose { servo_id: 1, degree: 0 };
        families.get_mut(Family::Plen2).act(&mut shell, Box::new(action));
    }
}
