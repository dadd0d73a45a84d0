//! The parent's depth buffer and its discretisation into n x n blocks of minimum
//! depth (Zou et al., Section 3.2, Steps 1-3 and Fig. 2): a point cloud renders to a
//! depth image full of holes; taking each block's minimum makes it "visually
//! continuous" so the cursor cannot fall through to the back surface (Fig. 3).

use super::camera::Camera;
use glam::{DVec2, DVec3};

/// Depth value of a pixel or block with no surface.
pub const EMPTY_DEPTH: f32 = 1.0;

/// A rendered depth image: one value per pixel, row-major from the top-left, and
/// where inside the pixel the kept sample projects (so it can be unprojected
/// exactly, not from the pixel centre).
#[derive(Debug, Clone, PartialEq)]
pub struct DepthImage {
    pub width: usize,
    pub height: usize,
    pub depth: Vec<f32>,
    pub position: Vec<DVec2>,
}

impl DepthImage {
    /// Renders `points` as one-pixel splats keeping the nearest depth (the "clean,
    /// then render M_p" of Section 3.2). The camera is assumed valid.
    pub fn render(points: &[DVec3], camera: &Camera) -> Self {
        let (width, height) = (camera.width, camera.height);
        let mut depth = vec![EMPTY_DEPTH; width * height];
        let mut position = vec![DVec2::ZERO; width * height];
        for &p in points {
            let Some((px, d)) = camera.project(p) else {
                continue;
            };
            if px.x < 0.0 || px.y < 0.0 {
                continue;
            }
            let (i, j) = (px.x as usize, px.y as usize);
            if i < width && j < height {
                let k = j * width + i;
                if (d as f32) < depth[k] {
                    depth[k] = d as f32;
                    position[k] = px;
                }
            }
        }
        Self {
            width,
            height,
            depth,
            position,
        }
    }

    /// Depth at pixel `(i, j)`; empty outside the image.
    pub fn at(&self, i: i64, j: i64) -> f32 {
        if i < 0 || j < 0 || i as usize >= self.width || j as usize >= self.height {
            return EMPTY_DEPTH;
        }
        self.depth[j as usize * self.width + i as usize]
    }
}

/// The discrete depth buffer M: the image split into `n x n` blocks (the last row
/// and column may be partial), each holding its minimum depth and where that
/// sample projects.
#[derive(Debug, Clone, PartialEq)]
pub struct BlockDepth {
    pub block: usize,
    pub cols: usize,
    pub rows: usize,
    pub depth: Vec<f32>,
    pub position: Vec<DVec2>,
}

impl BlockDepth {
    /// Steps 1-3 of Section 3.2 with block size `n` (at least 1; the paper uses 10).
    pub fn from_image(image: &DepthImage, n: usize) -> Self {
        let n = n.max(1);
        let cols = image.width.div_ceil(n);
        let rows = image.height.div_ceil(n);
        let mut depth = vec![EMPTY_DEPTH; cols * rows];
        let mut position = vec![DVec2::ZERO; cols * rows];
        for j in 0..image.height {
            for i in 0..image.width {
                let k = (j / n) * cols + i / n;
                let d = image.depth[j * image.width + i];
                if d < depth[k] {
                    depth[k] = d;
                    position[k] = image.position[j * image.width + i];
                }
            }
        }
        Self {
            block: n,
            cols,
            rows,
            depth,
            position,
        }
    }

    /// The block holding pixel `(i, j)`, or `None` outside the image.
    pub fn block_of(&self, i: i64, j: i64) -> Option<(usize, usize)> {
        let n = self.block as i64;
        if i < 0 || j < 0 || i / n >= self.cols as i64 || j / n >= self.rows as i64 {
            return None;
        }
        Some(((i / n) as usize, (j / n) as usize))
    }

    /// Depth of block `(c, r)`; empty outside.
    pub fn block_depth(&self, c: i64, r: i64) -> f32 {
        if c < 0 || r < 0 || c as usize >= self.cols || r as usize >= self.rows {
            return EMPTY_DEPTH;
        }
        self.depth[r as usize * self.cols + c as usize]
    }

    /// Discretised depth at pixel `(i, j)`.
    pub fn at_pixel(&self, i: i64, j: i64) -> f32 {
        self.block_of(i, j)
            .map_or(EMPTY_DEPTH, |(c, r)| self.block_depth(c as i64, r as i64))
    }

    /// Whether pixel `(i, j)` shows the surface (depth below 1.0).
    pub fn on_surface(&self, i: i64, j: i64) -> bool {
        self.at_pixel(i, j) < EMPTY_DEPTH
    }

    /// Centre of block `(c, r)` in pixel coordinates.
    pub fn block_centre(&self, c: i64, r: i64) -> DVec2 {
        let n = self.block as f64;
        DVec2::new((c as f64 + 0.5) * n, (r as f64 + 0.5) * n)
    }

    /// The surface sample that gave block `(c, r)` its depth, as pixel position
    /// and depth; `None` for empty blocks.
    pub fn sample(&self, c: i64, r: i64) -> Option<(DVec2, f32)> {
        let d = self.block_depth(c, r);
        (d < EMPTY_DEPTH).then(|| (self.position[r as usize * self.cols + c as usize], d))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn blocks_take_the_minimum() {
        let image = DepthImage {
            width: 5,
            height: 3,
            position: vec![DVec2::ZERO; 15],
            depth: vec![
                1.0, 0.5, 1.0, 1.0, 1.0, //
                1.0, 1.0, 1.0, 0.7, 1.0, //
                0.2, 1.0, 1.0, 1.0, 0.9,
            ],
        };
        let blocks = BlockDepth::from_image(&image, 2);
        assert_eq!((blocks.cols, blocks.rows), (3, 2));
        assert_eq!(blocks.depth, vec![0.5, 0.7, 1.0, 0.2, 1.0, 0.9]);
        assert!(blocks.on_surface(1, 1) && !blocks.on_surface(4, 0) && !blocks.on_surface(-1, 0));
    }
}
