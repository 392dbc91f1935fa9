//! Validation of the rFLEX section.

use super::{Location, Problem, ProblemKind, Problems, Severity};
use crate::project::rflex::RflexProject;

/// Every problem of an rFLEX section.
pub fn validate_rflex(project: &RflexProject) -> Problems {
    let conversion = project.robot.conversion();
    let drive = project.drive;
    [
        ("distance_units_per_m", conversion.distance_units_per_m),
        ("angle_units_per_rad", conversion.angle_units_per_rad),
        ("max_speed_m_per_s", drive.max_speed_m_per_s),
        ("max_turn_rad_per_s", drive.max_turn_rad_per_s),
        ("accel_m_per_s2", drive.accel_m_per_s2),
    ]
    .into_iter()
    .filter(|(_, value)| !(value.is_finite() && *value > 0.0))
    .map(|(field, _)| Problem {
        severity: Severity::Error,
        location: Location::Robot,
        kind: ProblemKind::NotPositive { field },
    })
    .collect()
}
