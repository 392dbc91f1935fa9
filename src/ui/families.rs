//! The families the editor knows, each with its side of the editor
//! ([`FamilyUi`]), gathered from the registry each family adds itself to in
//! its own folder ([`Registered`]): no file lists them. The shell reaches a
//! family through this list only; tests and a family's own code reach their
//! concrete type with [`Families::of`].

use std::any::Any;

use crate::project::Family;
use crate::ui::family::FamilyUi;

/// Each family's side of the editor, in menu order.
pub struct Families(Vec<Box<dyn FamilyUi>>);

/// A family's side of the editor in the registry: each family adds itself
/// (`inventory::submit!`) in its own folder, so that no file lists them all.
pub struct Registered {
    /// Its side of the editor as it starts.
    pub make: fn() -> Box<dyn FamilyUi>,
}

inventory::collect!(Registered);

impl Default for Families {
    fn default() -> Self {
        let mut uis: Vec<Box<dyn FamilyUi>> =
            inventory::iter::<Registered>.into_iter().map(|entry| (entry.make)()).collect();
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
}
