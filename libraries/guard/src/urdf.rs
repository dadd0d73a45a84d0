//! URDF import for serial arms: `<link>` with `<collision>` spheres, cylinders
//! (as the capsules that cover them) and boxes (as their circumscribed sphere),
//! and `<joint>` of type revolute, continuous, prismatic or fixed with
//! `<origin>`, `<parent>`, `<child>`, `<axis>` and `<limit>`. The joints must
//! form one unbranched chain. Meshes are refused: dropping a collision shape
//! silently would make the guard unsafe. Visual and inertial data are ignored.

use super::arm::{ArmModel, Link};
use super::error::GuardError;
use super::joint::{origin_from_xyz_rpy, Joint, JointKind};
use super::shape::Shape;
use super::xml::{parse, Element};
use glam::{DAffine3, DVec3};
use std::collections::{HashMap, HashSet};

impl ArmModel {
    /// A serial arm from URDF text; `base` is the world pose of the root link
    /// (URDF does not give one).
    pub fn from_urdf_str(text: &str, base: DAffine3) -> Result<ArmModel, GuardError> {
        let root = parse(text).map_err(GuardError::Urdf)?;
        if root.name != "robot" {
            return Err(urdf(format!(
                "the root element is <{}>, not <robot>",
                root.name
            )));
        }
        let mut links = HashMap::new();
        let mut order = Vec::new();
        for l in root.children_named("link") {
            let name = required(l, "name", "link")?;
            let shapes = l
                .children_named("collision")
                .map(|c| collision_shape(name, c))
                .collect::<Result<Vec<_>, _>>()?;
            if links.insert(name.to_string(), shapes).is_some() {
                return Err(GuardError::DuplicateName {
                    kind: "link",
                    name: name.into(),
                });
            }
            order.push(name.to_string());
        }
        let joints = root
            .children_named("joint")
            .map(RawJoint::of)
            .collect::<Result<Vec<_>, _>>()?;
        let chain = serial_chain(&order, &joints)?;
        let mut arm_links = Vec::with_capacity(chain.len() + 1);
        let mut arm_joints = Vec::with_capacity(chain.len());
        let first = match chain.first() {
            Some(&j) => joints[j].parent.clone(),
            None => order
                .first()
                .cloned()
                .ok_or_else(|| urdf("no <link>".into()))?,
        };
        let mut take = |name: &str| Link {
            name: name.to_string(),
            shapes: links.remove(name).unwrap_or_default(),
        };
        arm_links.push(take(&first));
        for &j in &chain {
            let raw = &joints[j];
            arm_joints.push(raw.joint()?);
            arm_links.push(take(&raw.child));
        }
        let name = root.attribute("name").unwrap_or("arm");
        ArmModel::new(name, base, arm_links, arm_joints)
    }
}

fn urdf(message: String) -> GuardError {
    GuardError::Urdf(message)
}

fn required<'a>(e: &'a Element, attribute: &str, what: &str) -> Result<&'a str, GuardError> {
    e.attribute(attribute)
        .ok_or_else(|| urdf(format!("<{what}> needs a '{attribute}' attribute")))
}

/// `N` whitespace-separated numbers.
fn numbers<const N: usize>(text: &str, what: &str) -> Result<[f64; N], GuardError> {
    let parsed: Vec<f64> = text
        .split_whitespace()
        .map(str::parse)
        .collect::<Result<_, _>>()
        .map_err(|_| urdf(format!("{what}: '{text}' is not a list of numbers")))?;
    parsed
        .try_into()
        .map_err(|_| urdf(format!("{what}: '{text}' should hold {N} numbers")))
}

/// `<origin xyz rpy>` (each optional, default zero) of an element.
fn origin(parent: &Element, what: &str) -> Result<DAffine3, GuardError> {
    let o = parent.child("origin");
    let get = |key: &str| match o.and_then(|o| o.attribute(key)) {
        Some(text) => numbers::<3>(text, &format!("{what} origin {key}")),
        None => Ok([0.0; 3]),
    };
    origin_from_xyz_rpy(&format!("{what} origin"), get("xyz")?, get("rpy")?)
}

/// One `<collision>`: a sphere, a capsule covering a cylinder (along the
/// collision frame's z), or the sphere around a box.
fn collision_shape(link: &str, c: &Element) -> Result<Shape, GuardError> {
    let what = format!("link '{link}' collision");
    let frame = origin(c, &what)?;
    let geometry = c
        .child("geometry")
        .and_then(|g| g.children.first())
        .ok_or_else(|| urdf(format!("{what} has no geometry")))?;
    let number = |key: &str| -> Result<f64, GuardError> {
        numbers::<1>(required(geometry, key, &geometry.name)?, &what).map(|[x]| x)
    };
    let centre = frame.transform_point3(DVec3::ZERO);
    match geometry.name.as_str() {
        "sphere" => Ok(Shape::sphere(centre, number("radius")?)),
        "cylinder" => {
            let (radius, length) = (number("radius")?, number("length")?);
            if !(length.is_finite() && length >= 0.0) {
                return Err(urdf(format!("{what}: cylinder length {length}")));
            }
            let half = DVec3::new(0.0, 0.0, 0.5 * length);
            Ok(Shape::capsule(
                frame.transform_point3(-half),
                frame.transform_point3(half),
                radius,
            ))
        }
        "box" => {
            let size = numbers::<3>(required(geometry, "size", "box")?, &what)?;
            Ok(Shape::sphere(
                centre,
                0.5 * DVec3::from_array(size).length(),
            ))
        }
        other => Err(urdf(format!(
            "{what}: <{other}> geometry is not supported (sphere, cylinder, box)"
        ))),
    }
}

/// A `<joint>` as read.
struct RawJoint {
    name: String,
    kind: JointKind,
    origin: [[f64; 3]; 2],
    parent: String,
    child: String,
    axis: [f64; 3],
    limits: Option<[f64; 2]>,
}

impl RawJoint {
    fn of(e: &Element) -> Result<Self, GuardError> {
        let name = required(e, "name", "joint")?.to_string();
        let what = format!("joint '{name}'");
        let (kind, limited) = match required(e, "type", "joint")? {
            "revolute" => (JointKind::Revolute, true),
            "continuous" => (JointKind::Revolute, false),
            "prismatic" => (JointKind::Prismatic, true),
            "fixed" => (JointKind::Fixed, false),
            other => return Err(urdf(format!("{what}: type '{other}' is not supported"))),
        };
        let link_of = |tag: &str| -> Result<String, GuardError> {
            let el = e
                .child(tag)
                .ok_or_else(|| urdf(format!("{what} has no <{tag}>")))?;
            Ok(required(el, "link", tag)?.to_string())
        };
        let o = e.child("origin");
        let get = |key: &str| match o.and_then(|o| o.attribute(key)) {
            Some(text) => numbers::<3>(text, &format!("{what} origin {key}")),
            None => Ok([0.0; 3]),
        };
        let axis = match e.child("axis").and_then(|a| a.attribute("xyz")) {
            Some(text) => numbers::<3>(text, &format!("{what} axis"))?,
            None => [1.0, 0.0, 0.0],
        };
        let limits = match (limited, e.child("limit")) {
            (true, Some(l)) => {
                let bound = |key: &str| match l.attribute(key) {
                    Some(text) => numbers::<1>(text, &format!("{what} limit {key}")).map(|[x]| x),
                    None => Ok(0.0),
                };
                Some([bound("lower")?, bound("upper")?])
            }
            _ => None,
        };
        Ok(Self {
            kind,
            origin: [get("xyz")?, get("rpy")?],
            parent: link_of("parent")?,
            child: link_of("child")?,
            axis,
            limits,
            name,
        })
    }

    fn joint(&self) -> Result<Joint, GuardError> {
        Joint::new(
            &self.name,
            self.kind,
            self.axis,
            self.origin[0],
            self.origin[1],
            self.limits,
        )
    }
}

/// The joints in chain order from the one root link; refuses branches, cycles,
/// unknown links and links or joints left out of the chain.
fn serial_chain(links: &[String], joints: &[RawJoint]) -> Result<Vec<usize>, GuardError> {
    let known: HashSet<&str> = links.iter().map(String::as_str).collect();
    for j in joints {
        for l in [&j.parent, &j.child] {
            if !known.contains(l.as_str()) {
                return Err(urdf(format!("joint '{}' names unknown link '{l}'", j.name)));
            }
        }
    }
    let children: HashSet<&str> = joints.iter().map(|j| j.child.as_str()).collect();
    let roots: Vec<&String> = links
        .iter()
        .filter(|l| !children.contains(l.as_str()))
        .collect();
    let [root] = roots.as_slice() else {
        return Err(urdf(format!(
            "a serial chain has one root link, found {}: {roots:?}",
            roots.len()
        )));
    };
    let mut chain = Vec::new();
    let mut current = root.as_str();
    let mut seen = HashSet::from([current]);
    loop {
        let next: Vec<usize> = (0..joints.len())
            .filter(|&i| joints[i].parent == current)
            .collect();
        match next.as_slice() {
            [] => break,
            [j] => {
                let child = joints[*j].child.as_str();
                if !seen.insert(child) {
                    return Err(urdf(format!("the joints form a cycle at link '{child}'")));
                }
                chain.push(*j);
                current = child;
            }
            _ => {
                return Err(urdf(format!(
                    "link '{current}' has {} child joints: not a serial chain",
                    next.len()
                )))
            }
        }
    }
    if chain.len() != joints.len() || seen.len() != links.len() {
        return Err(urdf(format!(
            "{} of {} joints and {} of {} links form the chain from '{root}'",
            chain.len(),
            joints.len(),
            seen.len(),
            links.len()
        )));
    }
    Ok(chain)
}

#[cfg(test)]
mod tests {
    use super::*;

    const TWO_LINK: &str = r#"<?xml version="1.0"?>
<robot name="two">
  <link name="base">
    <visual><geometry><mesh filename="ignored.stl"/></geometry></visual>
    <collision><origin xyz="0 0 0.05"/><geometry><sphere radius="0.1"/></geometry></collision>
  </link>
  <link name="arm">
    <collision>
      <origin xyz="0 0 0.25" rpy="0 0 0"/>
      <geometry><cylinder radius="0.04" length="0.5"/></geometry>
    </collision>
    <collision><origin xyz="0 0 0.5"/><geometry><box size="0.1 0.2 0.2"/></geometry></collision>
  </link>
  <link name="tool"/>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="arm"/>
    <origin xyz="0 0 0.1" rpy="0 0 0"/>
    <axis xyz="0 1 0"/>
    <limit lower="-1.5" upper="1.5" effort="10" velocity="1"/>
  </joint>
  <joint name="flange" type="fixed">
    <parent link="arm"/><child link="tool"/>
    <origin xyz="0 0 0.5"/>
  </joint>
</robot>"#;

    #[test]
    fn imports_a_serial_arm() {
        let arm = ArmModel::from_urdf_str(TWO_LINK, DAffine3::IDENTITY).unwrap();
        assert_eq!(arm.name(), "two");
        assert_eq!((arm.dof(), arm.links().len(), arm.shape_count()), (1, 3, 3));
        let Shape::Capsule(c) = arm.links()[1].shapes[0] else {
            panic!("a cylinder becomes a capsule")
        };
        assert!(
            (c.a - DVec3::ZERO).length() < 1e-12
                && (c.b - DVec3::new(0.0, 0.0, 0.5)).length() < 1e-12
        );
        let Shape::Sphere(b) = arm.links()[1].shapes[1] else {
            panic!("a box becomes a sphere")
        };
        assert!((b.radius - 0.15).abs() < 1e-12);
        assert_eq!(arm.joints()[0].limits().map(|l| l.upper), Some(1.5));
        // At q = 0 the box centre sits at z = 0.1 + 0.5.
        let pose = arm.forward(&[0.0]).unwrap();
        let Shape::Sphere(s) = pose.shapes[2].shape else {
            panic!("sphere")
        };
        assert!((s.centre - DVec3::new(0.0, 0.0, 0.6)).length() < 1e-12);
    }

    #[test]
    fn refuses_what_it_cannot_guard() {
        let bad = |from: &str, to: &str| {
            ArmModel::from_urdf_str(&TWO_LINK.replace(from, to), DAffine3::IDENTITY)
        };
        assert!(
            matches!(bad("<sphere radius=\"0.1\"/>", "<mesh filename=\"a.stl\"/>"), Err(GuardError::Urdf(m)) if m.contains("not supported"))
        );
        assert!(matches!(
            bad("type=\"fixed\"", "type=\"floating\""),
            Err(GuardError::Urdf(_))
        ));
        assert!(matches!(
            bad("<child link=\"tool\"/>", "<child link=\"nowhere\"/>"),
            Err(GuardError::Urdf(_))
        ));
        // A branch: the flange hangs off the base too.
        assert!(
            matches!(bad("<parent link=\"arm\"/><child link=\"tool\"/>", "<parent link=\"base\"/><child link=\"tool\"/>"), Err(GuardError::Urdf(m)) if m.contains("serial"))
        );
        assert!(matches!(
            bad("radius=\"0.1\"", "radius=\"-0.1\""),
            Err(GuardError::BadRadius { .. })
        ));
        assert!(matches!(
            bad("xyz=\"0 1 0\"", "xyz=\"0 0 0\""),
            Err(GuardError::BadAxis { .. })
        ));
        assert!(matches!(
            bad("xyz=\"0 1 0\"", "xyz=\"0 one 0\""),
            Err(GuardError::Urdf(_))
        ));
        assert!(matches!(
            bad("<robot name=\"two\">", "<robat name=\"two\">"),
            Err(GuardError::Urdf(_))
        ));
        assert!(matches!(
            bad(
                "<link name=\"tool\"/>",
                "<link name=\"tool\"/><link name=\"stray\"/>"
            ),
            Err(GuardError::Urdf(_))
        ));
        assert!(matches!(
            bad("upper=\"1.5\"", "upper=\"-2\""),
            Err(GuardError::BadLimits { .. })
        ));
        assert!(ArmModel::from_urdf_str("not xml", DAffine3::IDENTITY).is_err());
    }

    #[test]
    fn continuous_joints_have_no_limits() {
        let text = TWO_LINK.replace("type=\"revolute\"", "type=\"continuous\"");
        let arm = ArmModel::from_urdf_str(&text, DAffine3::IDENTITY).unwrap();
        assert_eq!(arm.joints()[0].limits(), None);
        assert_eq!(arm.joints()[0].kind(), JointKind::Revolute);
    }
}
