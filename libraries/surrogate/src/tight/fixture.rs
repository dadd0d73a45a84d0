//! Small clouds, their plain fits and candidate sets, shared by this module's tests.

use super::cloud_side::CloudSide;
use super::lp_reference::candidate_indices;
use crate::{fit_surrogate, Candidate, FitOptions, Side, Surrogate, Tightness};

pub struct Fixture {
    pub points: Vec<[f32; 3]>,
    pub options: FitOptions,
    /// The plain (heuristic) fit.
    pub plain: Surrogate,
}

impl Fixture {
    pub fn spheres(points: usize, grid: usize, time: f64) -> Self {
        let cloud = shroud_sim::MovingSpheres {
            points,
            ..Default::default()
        }
        .generate(time)
        .unwrap();
        Self::of(cloud, grid)
    }

    pub fn terrain(points: usize, grid: usize) -> Self {
        Self::of(
            shroud_sim::Terrain {
                points,
                ..Default::default()
            }
            .generate()
            .unwrap(),
            grid,
        )
    }

    fn of(points: Vec<[f32; 3]>, grid: usize) -> Self {
        let options = FitOptions {
            cols: grid,
            rows: grid,
            tightness: Tightness::Plain,
            ..Default::default()
        };
        let plain = fit_surrogate(&points, &options).unwrap();
        Self {
            points,
            options,
            plain,
        }
    }

    pub fn cloud(&self) -> CloudSide<'_> {
        CloudSide::of(&self.plain, &self.points, Side::Upper)
    }

    /// The fitter's candidates (upper sense).
    pub fn candidates(&self) -> Vec<Candidate> {
        let cloud = self.cloud();
        let all: Vec<Candidate> = cloud.constraints().collect();
        candidate_indices(&cloud, self.options.sub_cells)
            .iter()
            .map(|&i| all[i as usize])
            .collect()
    }

    pub fn fit(&self, tightness: Tightness) -> Surrogate {
        fit_surrogate(
            &self.points,
            &FitOptions {
                tightness,
                ..self.options.clone()
            },
        )
        .unwrap()
    }
}
