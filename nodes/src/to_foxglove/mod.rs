//! shroud's messages as Foxglove's well-known schemas (`foxglove.PointCloud`,
//! `foxglove.SceneUpdate`, `foxglove.FrameTransforms`) and as JSON views whose
//! numeric fields the Plot panel reads: what the Foxglove bridge serves and
//! what a recording stores beside the raw messages. Pure conversions of decoded
//! messages, no server and no I/O; the geometry itself (decimation, trimmed
//! meshes, the posed arm, clearance bands) is `shroud_viewers::scene`'s.

mod arm;
mod cloud;
mod geometry;
mod json;
mod schema;
mod surrogate;
mod topics;

pub use arm::{arm_scene, arm_transforms, vouched_bands, vouched_speed};
pub use cloud::point_cloud;
pub use geometry::{timestamp, WORLD_FRAME};
pub use json::{
    certificate_view, status_view, verdict_view, CertificateView, LinkView, StatusView,
    SurfaceCertificate, VerdictView, VERDICT_PERIOD_NS,
};
pub use schema::schema_of;
pub use surrogate::{surrogate_scene, SURFACE_PER_CELL};
pub use topics::{
    arm_scene_topic, arm_transforms_topic, certificate_topic, cloud_topic, status_topic,
    surrogate_topic, verdict_topic, BLEND_TOPIC,
};

#[cfg(test)]
pub(crate) mod fixtures {
    //! Messages the conversions' tests share.

    use shroud_msg::{CollisionMessage, GuardVerdict, LinkClearance};

    /// A clear verdict of arm `arm` with these (link, clearance, unobserved).
    pub fn collision(links: &[(&str, f64, bool)]) -> CollisionMessage {
        CollisionMessage {
            version: CollisionMessage::VERSION,
            joints_stamp_ns: 1,
            joints_sequence: 2,
            arm: "arm".into(),
            surrogate_stamp_ns: 3,
            surrogate_sequence: 4,
            surrogate_age_ns: 5,
            views: 1,
            verdict: GuardVerdict::Clear,
            stop: false,
            reason: String::new(),
            stop_distance: 0.05,
            min_clearance: 0.2,
            closest_link: links.first().map_or("", |l| l.0).into(),
            unobserved: false,
            links: links
                .iter()
                .map(|&(link, clearance, unobserved)| LinkClearance {
                    link: link.into(),
                    clearance,
                    unobserved,
                })
                .collect(),
            check_ns: 900,
            speed_scale: 1.0,
            limiting_link: String::new(),
            protective_distance: 0.05,
        }
    }
}
