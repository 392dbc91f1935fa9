//! Validation of a project's gamepad bindings (its own family's).

use super::super::document::Project;
use super::super::gamepad::{AxisTarget, Conflict, Fire};
use super::{Location, Problem, ProblemKind, Severity};

/// The family's gamepad bindings: what they fire or move exists, and nothing
/// is bound twice (warnings: the bindings are the editor's, not the robot's;
/// a PLEN2 motion may be on the robot without being in the project).
pub(super) fn gamepad(project: &Project) -> Vec<Problem> {
    let mapping = project.gamepad.of(project.family);
    let warning = |location, kind| Problem { severity: Severity::Warning, location, kind };
    let mut problems = Vec::new();
    for binding in &mapping.buttons {
        let missing = match binding.fire {
            Fire::Action(action_id) if project.servo.action(action_id).is_none() => {
                Some(ProblemKind::MissingAction { action_id })
            }
            Fire::Macro(macro_id) if project.servo.macro_by_id(macro_id).is_none() => {
                Some(ProblemKind::MissingMacro { macro_id })
            }
            Fire::PlayList(index) if index >= project.plen2.play_lists.len() => {
                Some(ProblemKind::MissingPlayList { index: index + 1 })
            }
            _ => None,
        };
        problems.extend(missing.map(|kind| warning(Location::GamepadButton { button: binding.button }, kind)));
    }
    for binding in &mapping.axes {
        if let AxisTarget::Servo(servo_id) = binding.target
            && project.servo.servo(servo_id).is_none()
        {
            problems
                .push(warning(Location::GamepadAxis { axis: binding.axis }, ProblemKind::MissingServo { servo_id }));
        }
    }
    // The rFLEX dead-man is the base's own: `ui` reserves it; here only twice-bound is said.
    for conflict in mapping.conflicts(&[]) {
        let location = match conflict {
            Conflict::Button(button) | Conflict::Reserved(button) => Location::GamepadButton { button },
            Conflict::Target(target) => {
                let axis =
                    mapping.axes.iter().find(|binding| binding.target == target).map_or(0, |binding| binding.axis);
                Location::GamepadAxis { axis }
            }
        };
        problems.push(warning(location, ProblemKind::BoundTwice));
    }
    problems
}

#[cfg(test)]
mod tests {
    use super::super::validate;
    use super::*;

    #[test]
    fn a_twin_outside_the_rig_and_gamepad_bindings_to_nothing_or_twice_are_warned_about() {
        use crate::project::gamepad::{AxisBinding, AxisTarget, ButtonBinding, Fire};
        use crate::project::{RigAxis, RigJoint, Servo, ServoProject};
        let rig = |mirror| RigJoint {
            parent: None,
            offset_mm: [0; 3],
            axis: RigAxis::Y,
            reversed: false,
            straight_deg: 0,
            mirror,
            end: None,
        };
        let mut servos = vec![Servo::new(1, "L"), Servo::new(2, "R"), Servo::new(3, "head")];
        servos[0].rig = Some(rig(Some(2)));
        servos[1].rig = Some(rig(Some(9)));
        servos[2].rig = Some(rig(Some(3)));
        let mut project = Project::servo(ServoProject { servos, ..ServoProject::default() });
        let button = |button, fire| ButtonBinding { button, fire };
        project.gamepad.servo.buttons =
            vec![button(0x130, Fire::Action(7)), button(0x131, Fire::Macro(8)), button(0x131, Fire::Stop)];
        project.gamepad.servo.axes = vec![AxisBinding::absolute(0, AxisTarget::Servo(42), (-90.0, 90.0))];
        let said: Vec<String> = validate(&project).iter().map(ToString::to_string).collect();
        assert_eq!(
            said,
            [
                "warning: servo 2 \"R\": its Mirror L/R twin is servo 9, which is not another servo of the rig: Mirror L/R keeps its steps; name a rigged servo on the other side",
                "warning: servo 3 \"head\": its Mirror L/R twin is servo 3, which is not another servo of the rig: Mirror L/R keeps its steps; name a rigged servo on the other side",
                "warning: gamepad button 0x130: action 7 does not exist",
                "warning: gamepad button 0x131: macro 8 does not exist",
                "warning: gamepad axis 0: servo 42 does not exist",
                "warning: gamepad button 0x131: is bound twice (or held by another use): only one of its bindings works; remove the others",
            ]
        );
        assert!(!validate(&project).has_errors(), "the bindings and twins are the editor's: nothing is refused");
    }
}
