//! Half-edge adjacency of a quad mesh: face, next, opposite per directed edge,
//! outgoing edges per vertex in rotation order, undirected edges and boundary loops.

use std::collections::HashMap;

use super::error::MeshError;

/// Half-edge connectivity. Half-edge `h = 4 * f + k` runs from corner `k` of face `f`
/// to corner `(k + 1) % 4`, so faces and `next` are implicit.
#[derive(Debug, Clone, PartialEq)]
pub struct HalfEdgeMesh {
    origin: Vec<u32>,
    opposite: Vec<Option<usize>>,
    edge_of: Vec<usize>,
    edges: Vec<usize>,
    outgoing: Vec<Vec<usize>>,
    boundary_loops: Vec<Vec<usize>>,
}

impl HalfEdgeMesh {
    /// Builds and validates the connectivity of `faces` over `vertex_count` vertices:
    /// indices in range, no repeated vertex in a face, every edge in at most two
    /// faces with opposite directions, every vertex used and surrounded by one fan.
    pub(crate) fn build(vertex_count: usize, faces: &[[u32; 4]]) -> Result<Self, MeshError> {
        for (f, face) in faces.iter().enumerate() {
            for (corner, &index) in face.iter().enumerate() {
                if index as usize >= vertex_count {
                    return Err(MeshError::IndexOutOfRange {
                        face: f,
                        corner,
                        index,
                        vertex_count,
                    });
                }
                if face[..corner].contains(&index) {
                    return Err(MeshError::DegenerateFace {
                        face: f,
                        vertex: index,
                    });
                }
            }
        }
        let origin: Vec<u32> = faces.iter().flat_map(|face| face.iter().copied()).collect();
        let half_edges = origin.len();

        // Undirected edge -> half-edges using it.
        let mut by_edge: HashMap<(u32, u32), Vec<usize>> = HashMap::with_capacity(half_edges);
        for h in 0..half_edges {
            let (a, b) = (origin[h], origin[next(h)]);
            by_edge.entry((a.min(b), a.max(b))).or_default().push(h);
        }
        let mut opposite = vec![None; half_edges];
        for h in 0..half_edges {
            let (a, b) = (origin[h], origin[next(h)]);
            let key = (a.min(b), a.max(b));
            let Some(users) = by_edge.get(&key) else {
                continue;
            };
            if users.first() != Some(&h) {
                continue;
            }
            let (a, b) = key;
            match users.as_slice() {
                [_] => {}
                &[h1, h2] => {
                    if origin[h1] == origin[h2] {
                        let (first, second) = (h1.min(h2) / 4, h1.max(h2) / 4);
                        return Err(MeshError::InconsistentOrientation {
                            a: origin[h1],
                            b: origin[next(h1)],
                            first,
                            second,
                        });
                    }
                    opposite[h1] = Some(h2);
                    opposite[h2] = Some(h1);
                }
                many => {
                    let mut fs: Vec<usize> = many.iter().map(|h| h / 4).collect();
                    fs.sort_unstable();
                    return Err(MeshError::NonManifoldEdge {
                        a,
                        b,
                        first: fs[0],
                        second: fs[1],
                        third: fs[2],
                    });
                }
            }
        }

        let mut edge_of = vec![usize::MAX; half_edges];
        let mut edges = Vec::new();
        for h in 0..half_edges {
            match opposite[h] {
                Some(o) if o < h => edge_of[h] = edge_of[o],
                _ => {
                    edge_of[h] = edges.len();
                    edges.push(h);
                }
            }
        }

        // Outgoing half-edges per vertex, then ordered by rotation.
        let mut unordered: Vec<Vec<usize>> = vec![Vec::new(); vertex_count];
        for (h, &v) in origin.iter().enumerate() {
            unordered[v as usize].push(h);
        }
        let mut outgoing = Vec::with_capacity(vertex_count);
        for (v, out) in unordered.into_iter().enumerate() {
            if out.is_empty() {
                return Err(MeshError::UnusedVertex { vertex: v });
            }
            let starts: Vec<usize> = out
                .iter()
                .copied()
                .filter(|&h| opposite[h].is_none())
                .collect();
            let start = match starts.as_slice() {
                [] => out[0],
                [s] => *s,
                _ => return Err(MeshError::NonManifoldVertex { vertex: v }),
            };
            let mut fan = vec![start];
            let mut h = start;
            while let Some(r) = opposite[prev(h)] {
                if r == start || fan.len() > out.len() {
                    break;
                }
                fan.push(r);
                h = r;
            }
            if fan.len() != out.len() {
                return Err(MeshError::NonManifoldVertex { vertex: v });
            }
            outgoing.push(fan);
        }

        // Boundary loops: follow boundary half-edges head to tail.
        let mut boundary_out: Vec<Option<usize>> = vec![None; vertex_count];
        for (h, opp) in opposite.iter().enumerate() {
            if opp.is_none() {
                boundary_out[origin[h] as usize] = Some(h);
            }
        }
        let mut seen = vec![false; half_edges];
        let mut boundary_loops = Vec::new();
        for h0 in 0..half_edges {
            if opposite[h0].is_some() || seen[h0] {
                continue;
            }
            let mut cycle = Vec::new();
            let mut h = h0;
            while !seen[h] {
                seen[h] = true;
                cycle.push(h);
                match boundary_out[origin[next(h)] as usize] {
                    Some(n) => h = n,
                    None => break,
                }
            }
            boundary_loops.push(cycle);
        }

        Ok(Self {
            origin,
            opposite,
            edge_of,
            edges,
            outgoing,
            boundary_loops,
        })
    }

    /// Number of half-edges (four per face).
    pub fn half_edge_count(&self) -> usize {
        self.origin.len()
    }

    /// Number of faces.
    pub fn face_count(&self) -> usize {
        self.origin.len() / 4
    }

    /// Number of vertices.
    pub fn vertex_count(&self) -> usize {
        self.outgoing.len()
    }

    /// The face that half-edge `h` belongs to.
    pub fn face(&self, h: usize) -> usize {
        h / 4
    }

    /// The next half-edge around the same face.
    pub fn next(&self, h: usize) -> usize {
        next(h)
    }

    /// The previous half-edge around the same face.
    pub fn prev(&self, h: usize) -> usize {
        prev(h)
    }

    /// The half-edge of the neighbouring face along the same edge, `None` on the boundary.
    pub fn opposite(&self, h: usize) -> Option<usize> {
        self.opposite[h]
    }

    /// The vertex `h` starts at.
    pub fn origin(&self, h: usize) -> u32 {
        self.origin[h]
    }

    /// The vertex `h` ends at.
    pub fn target(&self, h: usize) -> u32 {
        self.origin[next(h)]
    }

    /// Number of undirected edges.
    pub fn edge_count(&self) -> usize {
        self.edges.len()
    }

    /// The undirected edge half-edge `h` lies on.
    pub fn edge(&self, h: usize) -> usize {
        self.edge_of[h]
    }

    /// A half-edge on edge `e` (the only one for boundary edges).
    pub fn edge_half_edge(&self, e: usize) -> usize {
        self.edges[e]
    }

    /// The two endpoints of edge `e`.
    pub fn edge_vertices(&self, e: usize) -> [u32; 2] {
        let h = self.edges[e];
        [self.origin(h), self.target(h)]
    }

    /// Whether edge `e` belongs to one face only.
    pub fn is_boundary_edge(&self, e: usize) -> bool {
        self.opposite[self.edges[e]].is_none()
    }

    /// Half-edges leaving vertex `v`, one per incident face, in counter-clockwise
    /// order; for a boundary vertex the first one lies on the boundary.
    pub fn outgoing(&self, v: usize) -> &[usize] {
        &self.outgoing[v]
    }

    /// Whether `v` lies on a boundary edge.
    pub fn is_boundary_vertex(&self, v: usize) -> bool {
        self.outgoing[v]
            .first()
            .is_some_and(|&h| self.opposite[h].is_none())
    }

    /// Number of faces around `v`.
    pub fn faces_at(&self, v: usize) -> usize {
        self.outgoing[v].len()
    }

    /// The paper's valence: number of edges at `v` (faces + 1 on the boundary).
    pub fn valence(&self, v: usize) -> usize {
        self.faces_at(v) + usize::from(self.is_boundary_vertex(v))
    }

    /// The vertices joined to `v` by an edge, in counter-clockwise order.
    pub fn neighbours(&self, v: usize) -> Vec<u32> {
        let out = &self.outgoing[v];
        let mut result: Vec<u32> = out.iter().map(|&h| self.target(h)).collect();
        if self.is_boundary_vertex(v) {
            if let Some(&last) = out.last() {
                result.push(self.origin(prev(last)));
            }
        }
        result
    }

    /// Boundary loops as sequences of boundary half-edges, head to tail, each
    /// leaving the faces on its left.
    pub fn boundary_loops(&self) -> &[Vec<usize>] {
        &self.boundary_loops
    }

    /// The vertices of boundary loop `i`, in order.
    pub fn boundary_loop_vertices(&self, i: usize) -> Vec<u32> {
        self.boundary_loops[i]
            .iter()
            .map(|&h| self.origin(h))
            .collect()
    }
}

fn next(h: usize) -> usize {
    h - h % 4 + (h + 1) % 4
}

fn prev(h: usize) -> usize {
    h - h % 4 + (h + 3) % 4
}
