//! The PLEN2 figure against the official Motion Editor's 3D model
//! (`../shared/plen2/model/plen2_3dmodel.json`; skipped with a notice when
//! absent): at home, every joint of Servo Studio's chain sits where the
//! model's matrices put it and turns about the axis the model turns it about
//! (its node's local +Y), both sides — so a value bends a joint the way the
//! official editor, and the robot, bend it.

#![allow(clippy::unwrap_used, clippy::expect_used)]

use glam::{DMat4, DVec3};
use servo_studio::figure::plen2;
use servo_studio::protocol::plen2::Joint;

/// Each node named like a joint: its world matrix at home, in the model's frame.
fn model_joints(node: &serde_json::Value, parent: DMat4, out: &mut Vec<(String, DMat4)>) {
    let matrix = node["matrix"].as_array().map_or(DMat4::IDENTITY, |values| {
        let values: Vec<f64> = values.iter().map(|v| v.as_f64().unwrap()).collect();
        DMat4::from_cols_array(&values.try_into().unwrap())
    });
    let world = parent * matrix;
    let name = node["name"].as_str().unwrap_or_default();
    if ["roll", "pitch", "yaw"].iter().any(|end| name.ends_with(end)) {
        out.push((name.to_string(), world));
    }
    for child in node["children"].as_array().into_iter().flatten() {
        model_joints(child, world, out);
    }
}

/// The model is Y-up with the robot facing +Z and its left at +X; ours is x
/// forward, y left, z up (a rotation: handedness is kept).
fn ours(v: DVec3) -> DVec3 {
    DVec3::new(v.z, v.x, v.y)
}

#[test]
fn every_joint_sits_and_turns_where_the_official_model_has_it() {
    let Some(path) = crate::common::shared("plen2/model/plen2_3dmodel.json") else { return };
    let text = std::fs::read_to_string(path).unwrap();
    let model: serde_json::Value = serde_json::from_str(&text).unwrap();
    let mut joints = Vec::new();
    model_joints(&model["object"], DMat4::IDENTITY, &mut joints);
    assert_eq!(joints.len(), 18, "the model's joints: {:?}", joints.iter().map(|(n, _)| n).collect::<Vec<_>>());

    let chain = plen2::chain();
    let placed = chain.pose(&vec![0.0; chain.links.len()]);
    let at = |name: &str| {
        let link = chain.link(name).unwrap_or_else(|| panic!("no link {name}"));
        let place = placed[link];
        let axis = (place.rotation * chain.links[link].axis).normalize();
        (
            DVec3::new(f64::from(place.position.x), f64::from(place.position.y), f64::from(place.position.z)),
            DVec3::new(f64::from(axis.x), f64::from(axis.y), f64::from(axis.z)),
        )
    };
    let model_at = |name: &str| {
        let world = joints.iter().find(|(n, _)| n == name).unwrap().1;
        (ours(world.w_axis.truncate()), ours(world.transform_vector3(DVec3::Y).normalize()))
    };
    // Positions compared relative to the left shoulder (the two figures' origins differ).
    let reference = Joint::LeftShoulderPitch.name();
    let (ours_origin, _) = at(reference);
    let (model_origin, _) = model_at(reference);
    for joint in Joint::ALL {
        let (position, axis) = at(joint.name());
        let (model_position, model_axis) = model_at(joint.name());
        let offset = (position - ours_origin) - (model_position - model_origin);
        // The right side is the left mirrored; the model's sides agree to 0.1 unit, its
        // numbers were rounded to 0.1: a few tenths of a unit on a 540-unit figure.
        assert!(offset.length() < 0.5, "{}: {:?} off the model's place", joint.name(), offset);
        assert!(axis.dot(model_axis) > 0.999, "{}: turns about {axis:?}, the model about {model_axis:?}", joint.name());
    }
}
