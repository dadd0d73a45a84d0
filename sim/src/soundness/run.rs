//! Running soundness cases: per scene, scan with every sensor at its own
//! time, fit each cloud with shroud's fitter as the fit node does, feed the
//! views to a real `CollisionGuard` on one time axis, and check every
//! verdict for random arm poses and decision times against the truth.

use super::arms::{random_configuration, Arms};
use super::report::{Finding, FindingClass, SoundnessReport, MAX_FINDINGS};
use super::scene::{SensorSetup, SoundnessScene};
use super::sensors::EmptyRayIndex;
use super::solids::Solid;
use super::truth::{nearest, nearest_surface_point, solid_distance, Core};
use super::{SoundnessError, SoundnessParams};
use glam::DVec3;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use rayon::prelude::*;
use shroud_guard::{
    check_shapes, CollisionGuard, Envelope, GuardConfig, GuardPolicy, SurrogateInput, WorldShape,
};
use shroud_msg::{FieldOfView, GuardVerdict, NoReturn, DEFAULT_MAX_CLOCK_OFFSET_NS};
use shroud_surrogate::{fit_surrogate, FitOptions, SectorFitter, Surrogate};

/// The guard's monotonic clock reads this at scene time 0 (ns); its wall
/// clock reads `WALL_OFFSET_NS` more. One axis, as the brief of the harness
/// asks: ages are then exactly what the scene's timing says.
const MONO_AT_ZERO_NS: u64 = 1_000_000_000;
const WALL_OFFSET_NS: u64 = 1_750_000_000_000_000_000;

/// Largest extra wait from the last arrival to a decision (s).
const MAX_DECISION_DELAY: f64 = 0.3;

fn mono_ns(t: f64) -> u64 {
    MONO_AT_ZERO_NS + (t * 1e9).round() as u64
}

fn wall_ns(t: f64) -> u64 {
    mono_ns(t) + WALL_OFFSET_NS
}

/// The seed of scene `index` of a run seeded with `seed` (a splitmix64
/// step, so that neighbouring scenes are unrelated and each can be replayed
/// alone with [`run_case`]).
pub fn scene_seed(seed: u64, index: u64) -> u64 {
    let mut z = seed
        .wrapping_add(index.wrapping_mul(0x9e37_79b9_7f4a_7c15))
        .wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// Runs `cases` scenes (in parallel) and adds up their reports.
pub fn run(
    params: &SoundnessParams,
    cases: u64,
    seed: u64,
) -> Result<SoundnessReport, SoundnessError> {
    params.validate()?;
    let arms = Arms::load()?;
    (0..cases)
        .into_par_iter()
        .map(|i| run_case(&arms, params, scene_seed(seed, i)))
        .try_reduce(SoundnessReport::empty, |a, b| Ok(a.merged(b)))
}

/// Whether every shape, grown by the stop distance, lies in space one fresh
/// view saw free and that nothing unseen can have reached by the end of the
/// verdict: in one view not older than the guard's `max_age` (the harness's
/// own age: decision time less scan time, plus the clock offset the guard
/// adds), each core sample has a clear line of sight from the sensor at its
/// scan time, and lies deeper in the rays' hull and range
/// ([`Sensor::depth_in_view`](super::sensors::Sensor::depth_in_view),
/// exact) than the shape's radius, the stop distance and the way an obstacle
/// at the speed bound travels from the scan until the horizon. The depth is
/// concave, so the samples (a capsule's ends and middle) bound the whole
/// core. Each sample is as far from every ray that returned nothing, widened
/// by the gap between rays ([`Sensor::clearance_from_empty_rays`](super::sensors::Sensor::clearance_from_empty_rays)): a ray
/// without return proves no space free, since a black solid returns nothing
/// either (checked at the samples only, which can count a capsule whose
/// middle passes nearer an empty ray as seen: that only makes the figure
/// worse). A pose outside it has no provable `clear`, so it does not count
/// towards conservativeness.
fn in_seen_space(
    cores: &[Core],
    views: &[View],
    scene: &SoundnessScene,
    params: &SoundnessParams,
    decision: f64,
) -> bool {
    let offset = DEFAULT_MAX_CLOCK_OFFSET_NS as f64 * 1e-9;
    cores.iter().all(|c| {
        views.iter().any(|v| {
            let sensor = &v.setup.sensor;
            let age = (decision - sensor.time).max(0.0) + offset;
            let reach = c.radius
                + params.stop_distance
                + params.max_obstacle_speed * (age + params.horizon);
            v.envelope.is_some()
                && age <= params.max_age
                && c.samples().iter().all(|&p| {
                    sensor.sees(p, &scene.solids)
                        && sensor.depth_in_view(p) >= reach
                        && sensor.clearance_from_empty_rays(p, &v.empty) >= reach
                })
        })
    })
}

/// The smallest clearance any guard fed these views may clear at time `t`:
/// the stop distance plus the distance an obstacle at the speed bound covers
/// from the freshest fitted view's scan (with the clock offset the guard
/// adds) to the end of the horizon.
fn required_clearance(views: &[View], params: &SoundnessParams, t: f64) -> f64 {
    let offset = DEFAULT_MAX_CLOCK_OFFSET_NS as f64 * 1e-9;
    let age = views
        .iter()
        .filter(|v| v.envelope.is_some())
        .map(|v| (t - v.setup.sensor.time).max(0.0) + offset)
        .fold(f64::INFINITY, f64::min);
    params.stop_distance + params.max_obstacle_speed * (age + params.horizon)
}

/// One sensor's contribution: its cloud and, if it could be fitted, its view
/// and its sectors' views.
struct View {
    setup: SensorSetup,
    cloud: Vec<[f32; 3]>,
    /// Its rays that returned nothing ([`Sensor::empty_rays`](super::sensors::Sensor::empty_rays)).
    empty: EmptyRayIndex,
    envelope: Option<Envelope>,
    /// The views of its sectors that could be fitted (none unless
    /// `params.sectors` and a stated field of view).
    sectors: Vec<Envelope>,
}

impl View {
    /// The whole view's envelope, then its sectors'.
    fn envelopes(&self) -> impl Iterator<Item = &Envelope> {
        self.envelope.iter().chain(&self.sectors)
    }

    /// The guard views it takes: the whole view's, then one per sector.
    fn slots(&self) -> usize {
        1 + self.sectors.len()
    }
}

/// What a sensor's cloud states besides its points.
struct Statement {
    field_of_view: Option<FieldOfView>,
    no_return: Option<NoReturn>,
}

/// The fit node's options for a sensor's views (the direction is the whole
/// view's; each sector looks along its own axis).
fn options_of(setup: &SensorSetup) -> FitOptions {
    FitOptions {
        cols: setup.cols,
        rows: setup.rows,
        direction: setup.sensor.look.to_array(),
        sides: setup.sides,
        ..FitOptions::default()
    }
}

/// The guard's view of a surrogate with what its cloud states; `None` (the
/// guard then has one view fewer) for an envelope error.
fn envelope_of(
    surrogate: &Surrogate,
    field_of_view: Option<FieldOfView>,
    no_return: Option<&NoReturn>,
) -> Option<Envelope> {
    Envelope::new(surrogate)
        .ok()?
        .with_field_of_view(field_of_view)
        .ok()?
        .with_no_return(no_return)
        .ok()
}

/// The whole view of a sensor's cloud, fitted as the fit node would; `None`
/// for a cloud too small or a fit error.
fn whole_envelope(
    cloud: &[[f32; 3]],
    setup: &SensorSetup,
    stated: &Statement,
    params: &SoundnessParams,
) -> Option<Envelope> {
    if cloud.len() < params.min_points {
        return None;
    }
    let surrogate = fit_surrogate(cloud, &options_of(setup)).ok()?;
    envelope_of(&surrogate, stated.field_of_view, stated.no_return.as_ref())
}

/// The views of the `params.sectors x params.sectors` sectors of a cloud
/// that states its field of view, as a fit node with `--sectors` fits them
/// ([`SectorFitter`]); sectors with fewer than `params.min_points` points
/// are left out, as whole clouds are.
fn sector_envelopes(
    cloud: &[[f32; 3]],
    setup: &SensorSetup,
    stated: &Statement,
    params: &SoundnessParams,
) -> Vec<Envelope> {
    let Some(fov) = stated.field_of_view.filter(|_| params.sectors > 0) else {
        return Vec::new();
    };
    let Ok(mut fitter) = SectorFitter::new(params.sectors, params.sector_reach, options_of(setup))
    else {
        return Vec::new();
    };
    (0..fitter.count())
        .filter_map(|index| {
            let fit = fitter
                .fit(index, &fov, stated.no_return.as_ref(), cloud)
                .ok()
                .flatten()?;
            (fit.surrogate.stats.points >= params.min_points as u64).then_some(())?;
            envelope_of(
                &fit.surrogate,
                Some(fit.field_of_view),
                fit.no_return.as_ref(),
            )
        })
        .collect()
}

/// The scene's sensors scanned and fitted as the fit node would.
fn views_of(scene: &SoundnessScene, params: &SoundnessParams) -> Vec<View> {
    scene
        .sensors
        .iter()
        .map(|setup| {
            let scan = setup.sensor.scan(&scene.solids);
            let cloud = scan.points.clone();
            let stated = Statement {
                field_of_view: params
                    .state_field_of_view
                    .then(|| setup.sensor.stated_field_of_view())
                    .flatten(),
                no_return: params
                    .state_no_return
                    .then(|| setup.sensor.stated_no_return(&scan))
                    .flatten(),
            };
            let envelope = whole_envelope(&cloud, setup, &stated, params);
            let sectors = match envelope {
                Some(_) => sector_envelopes(&cloud, setup, &stated, params),
                None => Vec::new(),
            };
            View {
                setup: *setup,
                empty: setup.sensor.empty_rays(&scan),
                cloud,
                envelope,
                sectors,
            }
        })
        .collect()
}

/// A scene's views fed to a guard, ready for decisions.
struct Prepared {
    views: Vec<View>,
    guard: CollisionGuard,
    /// Largest sampling margin of the views.
    margin: f64,
    last_arrival: f64,
}

/// Scans and fits the scene and feeds the views to a new guard in the order
/// they arrive.
fn prepare(
    arms: &Arms,
    params: &SoundnessParams,
    scene: &SoundnessScene,
) -> Result<Prepared, SoundnessError> {
    let views = views_of(scene, params);
    let margin = views
        .iter()
        .filter(|v| v.envelope.is_some())
        .map(|v| v.setup.sensor.sampling_margin())
        .fold(0.0, f64::max);
    let arm = arms.get(scene.arm);
    let links: Vec<String> = arm.links().iter().map(|l| l.name.clone()).collect();
    let config = GuardConfig {
        stop_distance: params.stop_distance,
        max_report: 2.0 * params.stop_distance,
        refine_depth: 3,
        max_obstacle_speed: params.max_obstacle_speed,
        horizon: params.horizon,
    };
    let policy = GuardPolicy {
        max_age_ns: (params.max_age * 1e9).round() as u64,
        unobserved: params.unobserved,
        ..GuardPolicy::default()
    };
    // Guard views per sensor: its whole view (held even when it could not
    // be fitted, so that the guard has a view per sensor), then its sectors.
    let names = views
        .iter()
        .enumerate()
        .flat_map(|(k, v)| (0..v.slots()).map(move |j| format!("sensor{k}.{j}")))
        .collect();
    let mut guard = CollisionGuard::new(names, links, policy, config)?;
    let first_slot: Vec<usize> = views
        .iter()
        .scan(0, |next, v| {
            let first = *next;
            *next += v.slots();
            Some(first)
        })
        .collect();
    let mut order: Vec<usize> = (0..views.len()).collect();
    order.sort_by(|&a, &b| {
        views[a]
            .setup
            .arrival()
            .total_cmp(&views[b].setup.arrival())
    });
    for &k in &order {
        let s = &views[k].setup;
        let whole = views[k].envelope.iter().map(|e| (0, e));
        let sectors = views[k].sectors.iter().enumerate().map(|(j, e)| (j + 1, e));
        for (j, envelope) in whole.chain(sectors) {
            let input = SurrogateInput {
                envelope: envelope.clone(),
                stamp_ns: wall_ns(s.sensor.time),
                sequence: k as u64,
                pipeline_ns: (s.pipeline * 1e9).round() as u64,
                published_ns: wall_ns(s.sensor.time + s.pipeline),
                position_error: 0.0,
            };
            // On one clock axis nothing is refused; a refusal would show as
            // verdicts without that view, which the truth check still judges.
            let slot = first_slot[k] + j;
            let _ = guard.accept(slot, input, mono_ns(s.arrival()), wall_ns(s.arrival()));
        }
    }
    let last_arrival = views.iter().map(|v| v.setup.arrival()).fold(0.0, f64::max);
    Ok(Prepared {
        views,
        guard,
        margin,
        last_arrival,
    })
}

/// One scene: `params.verdicts_per_case` verdicts checked against the truth.
pub fn run_case(
    arms: &Arms,
    params: &SoundnessParams,
    seed: u64,
) -> Result<SoundnessReport, SoundnessError> {
    let scene = SoundnessScene::draw(params, seed);
    let Prepared {
        views,
        guard,
        margin,
        last_arrival,
    } = prepare(arms, params, &scene)?;
    let arm = arms.get(scene.arm);
    let mut report = SoundnessReport::empty();
    report.scenes = 1;
    report.points = views.iter().map(|v| v.cloud.len() as u64).sum();
    report.views = views.iter().filter(|v| v.envelope.is_some()).count() as u64;
    report.views_missing = views.len() as u64 - report.views;
    report.max_sampling_margin = margin;

    let mut rng = Pcg64::seed_from_u64(seed ^ 0x05ee_d0f9_05e5);
    let cutoff = 2.0 * params.stop_distance + 0.01;
    let threshold = params.stop_distance - margin;
    let mut remaining = params.verdicts_per_case;
    while remaining > 0 {
        let q = random_configuration(arm, &mut rng);
        let pose = arm.forward(&q)?;
        let cores: Vec<Core> = pose.shapes.iter().map(Core::of).collect();
        for _ in 0..params.timings_per_pose.min(remaining) {
            remaining -= 1;
            let t = last_arrival + rng.random_range(0.0..=MAX_DECISION_DELAY);
            let in_view = in_seen_space(&cores, &views, &scene, params, t);
            let decision = guard.decide(&pose.shapes, mono_ns(t))?;
            let truths: Vec<(f64, Option<usize>)> = cores
                .iter()
                .map(|c| nearest(c, &scene.solids, t, t + params.horizon, cutoff))
                .collect();
            let (worst, truth) = truths
                .iter()
                .enumerate()
                .min_by(|a, b| a.1 .0.total_cmp(&b.1 .0))
                .map(|(i, t)| (i, *t))
                .unwrap_or((0, (f64::INFINITY, None)));
            report.verdicts.count(decision.verdict);
            let judged = matches!(
                decision.verdict,
                GuardVerdict::Clear | GuardVerdict::Stop | GuardVerdict::Unobserved
            );
            if judged && in_view && truth.0 > 2.0 * params.stop_distance {
                let stopped = u64::from(decision.verdict != GuardVerdict::Clear);
                report.eligible += 1;
                report.eligible_stopped += stopped;
                report.eligible_unobserved +=
                    u64::from(decision.verdict == GuardVerdict::Unobserved);
                if truth.0 <= required_clearance(&views, params, t) {
                    report.eligible_forced += 1;
                    report.eligible_forced_stopped += stopped;
                }
            }
            if decision.verdict != GuardVerdict::Clear {
                continue;
            }
            report.closest_clear = report.closest_clear.min(truth.0);
            report.contacts += u64::from(truth.0 <= 0.0);
            if truth.0 < threshold {
                report.optimistic += 1;
                let shape = &pose.shapes[worst];
                let combined = decision.report.as_ref();
                let ctx = Context {
                    scene: &scene,
                    views: &views,
                    guard: &guard,
                    params,
                    margin,
                };
                let (class, vouching) = ctx.classify(shape, &cores[worst], truth.1, t);
                report.classes[class as usize] += 1;
                if report.findings.len() < MAX_FINDINGS {
                    report.findings.push(Finding {
                        scene_seed: seed,
                        arm: scene.arm,
                        joints: q.clone(),
                        shape_index: worst,
                        shape: shape.shape,
                        decision: t,
                        clearance: combined
                            .and_then(|r| r.shapes.get(worst))
                            .map_or(f64::NAN, |s| s.clearance),
                        min_clearance: combined.map_or(f64::NAN, |r| r.min_clearance),
                        truth: truth.0,
                        solid: truth.1,
                        sampling_margin: margin,
                        vouching_view: vouching,
                        vouching_sides: vouching.map(|k| views[k].setup.sides),
                        class,
                        scene_size: scene.solids.len() + scene.sensors.len(),
                        scene: scene.to_string(),
                    });
                }
            }
        }
    }
    Ok(report)
}

/// Whether the verdict for joint values `q` at time `t` in `scene` is
/// optimistic (clear, and some shape truly nearer than the stop distance
/// less the sampling margin).
fn is_optimistic(
    arms: &Arms,
    params: &SoundnessParams,
    scene: &SoundnessScene,
    q: &[f64],
    t: f64,
) -> Result<bool, SoundnessError> {
    let prepared = prepare(arms, params, scene)?;
    let pose = arms.get(scene.arm).forward(q)?;
    let decision = prepared.guard.decide(&pose.shapes, mono_ns(t))?;
    if decision.verdict != GuardVerdict::Clear {
        return Ok(false);
    }
    let threshold = params.stop_distance - prepared.margin;
    Ok(pose.shapes.iter().any(|s| {
        nearest(
            &Core::of(s),
            &scene.solids,
            t,
            t + params.horizon,
            threshold,
        )
        .0 < threshold
    }))
}

/// The finding's scene with every solid and sensor removed that the
/// optimistic verdict does not need (greedily, one at a time, the same arm
/// pose and decision time), or `None` when the finding does not replay.
pub fn minimise(
    params: &SoundnessParams,
    finding: &Finding,
) -> Result<Option<SoundnessScene>, SoundnessError> {
    let arms = Arms::load()?;
    let (q, t) = (&finding.joints, finding.decision);
    let mut scene = SoundnessScene::draw(params, finding.scene_seed);
    if !is_optimistic(&arms, params, &scene, q, t)? {
        return Ok(None);
    }
    for i in (0..scene.solids.len()).rev() {
        let mut smaller = scene.clone();
        smaller.solids.remove(i);
        if is_optimistic(&arms, params, &smaller, q, t)? {
            scene = smaller;
        }
    }
    for k in (0..scene.sensors.len()).rev() {
        let mut smaller = scene.clone();
        smaller.sensors.remove(k);
        if !smaller.sensors.is_empty() && is_optimistic(&arms, params, &smaller, q, t)? {
            scene = smaller;
        }
    }
    Ok(Some(scene))
}

/// What classifying a finding needs.
struct Context<'a> {
    scene: &'a SoundnessScene,
    views: &'a [View],
    guard: &'a CollisionGuard,
    params: &'a SoundnessParams,
    margin: f64,
}

impl Context<'_> {
    /// Which view vouched for the shape (the largest bound after its
    /// allowance, as the guard combines them; shroud's clearance code is
    /// used here only to attribute, never as truth), and why that view's
    /// sensor missed the obstacle, judged from the true geometry at its scan
    /// time.
    fn classify(
        &self,
        shape: &WorldShape,
        core: &Core,
        solid: Option<usize>,
        t: f64,
    ) -> (FindingClass, Option<usize>) {
        let config = self.guard.config();
        let one = [WorldShape { link: 0, ..*shape }];
        let clock_offset = DEFAULT_MAX_CLOCK_OFFSET_NS as f64 * 1e-9;
        let vouching = self
            .views
            .iter()
            .enumerate()
            .flat_map(|(k, v)| v.envelopes().map(move |e| (k, v, e)))
            .filter_map(|(k, v, envelope)| {
                let age = t - v.setup.sensor.time + clock_offset;
                if age > self.params.max_age {
                    return None;
                }
                let bound = check_shapes(envelope, &one, 1, config).ok()?.shapes[0].clearance;
                let allowance = config.max_obstacle_speed * (age + config.horizon);
                Some((k, bound, allowance))
            })
            .max_by(|a, b| (a.1 - a.2).total_cmp(&(b.1 - b.2)));
        let Some((k, bound, allowance)) = vouching else {
            return (FindingClass::Other, None);
        };
        let sensor = &self.views[k].setup.sensor;
        let solids: &[Solid] = &self.scene.solids;
        // The arm's point nearest the obstacle, and the obstacle's point
        // nearest to it where the sensor saw the scene.
        let target = |p: DVec3| match solid {
            Some(i) => nearest_surface_point(&solids[i], sensor.time, p),
            None => DVec3::new(p.x, p.y, 0.0),
        };
        let arm_point = core
            .samples()
            .into_iter()
            .min_by(|a, b| {
                (target(*a) - *a)
                    .length()
                    .total_cmp(&(target(*b) - *b).length())
            })
            .unwrap_or(core.a);
        let p = target(arm_point);
        // Nudged towards the sensor so that the surface itself does not
        // count as its own blocker.
        let nudged = sensor.origin + (p - sensor.origin) * (1.0 - 1e-6);
        let in_fov = sensor.covers(nudged);
        if !in_fov {
            return (FindingClass::FieldOfView, Some(k));
        }
        if solid.is_some_and(|i| solids[i].black) {
            return (FindingClass::BlackSolid, Some(k));
        }
        if !sensor.sees(nudged, solids) {
            return (FindingClass::Occlusion, Some(k));
        }
        // Seen in plain view: at the scan time the obstacle was this far.
        let then = match solid {
            Some(i) => solid_distance(core, &solids[i], sensor.time, sensor.time, f64::INFINITY),
            None => core.a.z.min(core.b.z) - core.radius,
        };
        if bound <= then + 1e-9 && bound - allowance >= config.stop_distance {
            return (FindingClass::Timing, Some(k));
        }
        let sampled = self.views[k].cloud.iter().any(|c| {
            (DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64) - p).length() <= self.margin
        });
        let class = if sampled {
            FindingClass::Other
        } else {
            FindingClass::Sampling
        };
        (class, Some(k))
    }
}
