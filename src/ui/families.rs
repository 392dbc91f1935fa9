//! The families the editor knows, each with its side of the editor
//! ([`FamilyUi`]): the one place in the ui that lists them. The shell reaches
//! a family through this list only; tests and a family's own code reach their
//! concrete type with [`Families::of`].

use std::any::Any;

use crate::project::Family;
use crate::ui::family::FamilyUi;
use crate::ui::plen2::Plen2Ui;
use crate::ui::rflex::RflexUi;
use crate::ui::servo::ServoUi;

/// Each family's side of the editor, one per [`Family::ALL`], in its order.
pub struct Families([Box<dyn FamilyUi>; Family::ALL.len()]);

/// The side of the editor of `family`, as it starts.
fn new_ui(family: Family) -> Box<dyn FamilyUi> {
    match family {
        Family::Servo => Box::<ServoUi>::default(),
        Family::Plen2 => Box::<Plen2Ui>::default(),
        Family::Rflex => Box::<RflexUi>::default(),
    }
}

impl Default for Families {
    fn default() -> Self {
        Self(Family::ALL.map(new_ui))
    }
}

impl std::fmt::Debug for Families {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_list().entries(self.0.iter().map(|family_ui| family_ui.family())).finish()
    }
}

impl Families {
    /// The side of the editor of `family`.
    pub fn get(&self, family: Family) -> &dyn FamilyUi {
        // `ALL` lists every family in declaration order: the discriminant is its place.
        &*self.0[family as usize]
    }

    /// The side of the editor of `family`, to change.
    pub fn get_mut(&mut self, family: Family) -> &mut dyn FamilyUi {
        &mut *self.0[family as usize]
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
    fn each_family_has_its_own_side_in_its_place() {
        let families = Families::default();
        for (place, family) in Family::ALL.into_iter().enumerate() {
            assert_eq!(family as usize, place, "ALL is in declaration order");
            assert_eq!(families.get(family).family(), family);
        }
        assert!(families.of::<ServoUi>().is_some() && families.of::<RflexUi>().is_some());
    }
}
