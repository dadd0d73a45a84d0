//! Tests of the quad-mesh module: validation, adjacency, classification,
//! Catmull-Clark refinement and OBJ bytes.

use super::*;

fn cube() -> QuadMesh {
    cube_mesh()
}

fn m_t() -> QuadMesh {
    triangle_mesh()
}

fn hexagon() -> QuadMesh {
    hexagon_mesh()
}

/// An n x n grid of unit quads in the plane z = 0, as raw parts.
fn grid(n: u32) -> (Vec<[f64; 3]>, Vec<[u32; 4]>) {
    rectangle_mesh([0.0; 2], [n as f64; 2], n)
        .unwrap()
        .into_parts()
}

fn check_half_edges(mesh: &QuadMesh) {
    let he = mesh.half_edges();
    assert_eq!(he.half_edge_count(), 4 * mesh.face_count());
    for h in 0..he.half_edge_count() {
        assert_eq!(he.prev(he.next(h)), h);
        assert_eq!(he.face(he.next(h)), he.face(h));
        if let Some(o) = he.opposite(h) {
            assert_eq!(he.opposite(o), Some(h));
            assert_eq!(he.origin(o), he.target(h));
            assert_eq!(he.target(o), he.origin(h));
            assert_eq!(he.edge(o), he.edge(h));
        }
    }
    for v in 0..mesh.vertex_count() {
        let out = he.outgoing(v);
        assert!(out.iter().all(|&h| he.origin(h) as usize == v));
        // Consecutive outgoing edges rotate through the shared edge.
        for w in out.windows(2) {
            assert_eq!(he.opposite(he.prev(w[0])), Some(w[1]));
        }
        assert_eq!(he.neighbours(v).len(), he.valence(v));
    }
    let boundary_edges = (0..he.edge_count())
        .filter(|&e| he.is_boundary_edge(e))
        .count();
    let in_loops: usize = he.boundary_loops().iter().map(Vec::len).sum();
    assert_eq!(boundary_edges, in_loops);
    for lp in he.boundary_loops() {
        for (i, &h) in lp.iter().enumerate() {
            assert!(he.opposite(h).is_none());
            assert_eq!(he.target(h), he.origin(lp[(i + 1) % lp.len()]));
        }
    }
}

#[test]
fn mesh_cube_is_closed_with_eight_valence_three_evs() {
    let cube = cube();
    check_half_edges(&cube);
    assert!(cube.is_closed());
    assert_eq!(cube.edge_count(), 12);
    assert_eq!(cube.euler_characteristic(), 2);
    let c = classify(&cube);
    assert_eq!((c.n_v, c.n_e, c.n_f), (8, 12, 6));
    assert_eq!(c.n_iev, 8);
    assert!(c.valences.iter().all(|&n| n == 3));
    assert_eq!((c.n_rv, c.n_brv, c.n_bev, c.n_c), (0, 0, 0, 0));
    assert_eq!((c.n_ee, c.n_re, c.n_be), (12, 0, 0));
    assert!(!c.has_isolated_evs());
}

#[test]
fn mesh_grid_classification() {
    let (v, f) = grid(3);
    let mesh = QuadMesh::new(v, f).expect("grid");
    check_half_edges(&mesh);
    assert!(!mesh.is_closed());
    assert_eq!(mesh.half_edges().boundary_loops().len(), 1);
    assert_eq!(mesh.half_edges().boundary_loop_vertices(0).len(), 12);
    let c = classify(&mesh);
    assert_eq!((c.n_v, c.n_e, c.n_f), (16, 24, 9));
    assert_eq!((c.n_rv, c.n_iev), (4, 0));
    assert_eq!((c.n_brv, c.n_bev, c.n_c), (8, 0, 4));
    assert_eq!((c.n_re, c.n_ee, c.n_be), (12, 0, 12));
    assert_eq!(c.valences[0], 2);
    assert_eq!(c.valences[1], 3);
    assert_eq!(c.valences[5], 4);
    assert!(c.has_isolated_evs());
    assert_eq!(c.vertices[0], VertexKind::Corner);
    // The first outgoing half-edge of a boundary vertex is on the boundary.
    let he = mesh.half_edges();
    assert!(he.opposite(he.outgoing(1)[0]).is_none());
}

#[test]
fn mesh_m_t_has_one_valence_three_ev() {
    let mesh = m_t();
    check_half_edges(&mesh);
    let c = classify(&mesh);
    assert_eq!((c.n_v, c.n_e, c.n_f), (7, 9, 3));
    assert_eq!(c.n_iev, 1);
    assert_eq!(c.vertices[6], VertexKind::InnerExtraordinary);
    assert_eq!(c.valences[6], 3);
    assert_eq!((c.n_c, c.n_brv, c.n_bev, c.n_rv), (3, 3, 0, 0));
    assert_eq!((c.n_ee, c.n_re, c.n_be), (3, 0, 6));
    assert!(c.has_isolated_evs());
    assert_eq!(mesh.half_edges().boundary_loops().len(), 1);
}

#[test]
fn mesh_boundary_extraordinary_vertex() {
    // Three quads fanned around a boundary vertex: kappa = 3 patches, valence N = 4.
    let vertices = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 1.0, 0.0],
        [-1.0, 1.0, 0.0],
        [-1.0, 0.0, 0.0],
        [-1.0, -1.0, 0.0],
        [0.0, -1.0, 0.0],
    ];
    let faces = vec![[0, 1, 2, 3], [0, 3, 4, 5], [0, 5, 6, 7]];
    let mesh = QuadMesh::new(vertices, faces).expect("fan");
    check_half_edges(&mesh);
    let c = classify(&mesh);
    assert_eq!(c.vertices[0], VertexKind::BoundaryExtraordinary);
    assert_eq!(c.valences[0], 4);
    assert_eq!((c.n_bev, c.n_ee), (1, 2));
}

#[test]
fn mesh_refinement_counts_closed() {
    let cube = cube();
    let once = catmull_clark(&cube).expect("refine");
    check_half_edges(&once);
    assert_eq!(once.face_count(), 24);
    assert_eq!(once.vertex_count(), 8 + 12 + 6);
    assert_eq!(once.edge_count(), 2 * 12 + 4 * 6);
    assert_eq!(once.euler_characteristic(), 2);
    let c = classify(&once);
    assert_eq!((c.n_iev, c.n_rv), (8, 18));
    assert!((0..8).all(|v| c.valences[v] == 3));
    assert!(c.has_isolated_evs());
    let twice = catmull_clark(&once).expect("refine");
    assert_eq!(twice.face_count(), 96);
    assert_eq!(twice.vertex_count(), 26 + 48 + 24);
    let c2 = classify(&twice);
    assert_eq!((c2.n_iev, c2.n_rv), (8, 90));
    // The cube is symmetric, so its refinement keeps the centroid.
    let n = twice.vertex_count() as f64;
    for k in 0..3 {
        let mean: f64 = twice.vertices().iter().map(|p| p[k]).sum::<f64>() / n;
        assert!((mean - 0.5).abs() < 1e-12);
    }
}

#[test]
fn mesh_refinement_of_open_meshes() {
    let mesh = m_t();
    let refined = catmull_clark(&mesh).expect("refine");
    check_half_edges(&refined);
    assert_eq!(refined.face_count(), 12);
    assert_eq!(refined.vertex_count(), 7 + 9 + 3);
    let c = classify(&refined);
    assert_eq!(c.vertices[6], VertexKind::InnerExtraordinary);
    assert_eq!((c.n_iev, c.n_bev, c.n_c), (1, 0, 3));
    // New vertices (edge and face points) are all regular.
    for v in 7..refined.vertex_count() {
        assert!(!c.vertices[v].is_extraordinary(), "vertex {v}");
        assert_ne!(c.vertices[v], VertexKind::Corner);
    }
    assert_eq!(c.n_brv, 3 + 6);
    assert_eq!(c.n_rv, 3 + 3);
    // Corners stay fixed.
    for v in 0..3 {
        assert_eq!(refined.vertices()[v], mesh.vertices()[v]);
    }

    // A regular planar grid refines to the grid of half the spacing.
    let (v, f) = grid(3);
    let g = QuadMesh::new(v, f).expect("grid");
    let r = catmull_clark(&g).expect("refine");
    assert_eq!(r.face_count(), 36);
    assert_eq!(r.vertex_count(), 16 + 24 + 9);
    for p in r.vertices() {
        assert_eq!(p[2], 0.0);
        assert_eq!((2.0 * p[0]).fract(), 0.0);
        assert_eq!((2.0 * p[1]).fract(), 0.0);
    }
    for (a, b) in r.vertices().iter().zip(g.vertices()) {
        assert_eq!(a, b);
    }
    let c = classify(&r);
    assert_eq!(
        (c.n_rv, c.n_brv, c.n_c, c.n_iev, c.n_bev),
        (25, 20, 4, 0, 0)
    );
}

#[test]
fn mesh_rejects_invalid_topology() {
    let p = vec![[0.0; 3]; 10];
    assert_eq!(
        QuadMesh::new(p.clone(), vec![]).unwrap_err(),
        MeshError::NoFaces
    );
    assert_eq!(
        QuadMesh::new(p[..4].to_vec(), vec![[0, 1, 2, 4]]).unwrap_err(),
        MeshError::IndexOutOfRange {
            face: 0,
            corner: 3,
            index: 4,
            vertex_count: 4
        }
    );
    assert_eq!(
        QuadMesh::new(p[..4].to_vec(), vec![[0, 1, 1, 3]]).unwrap_err(),
        MeshError::DegenerateFace { face: 0, vertex: 1 }
    );
    // Three faces on edge 0-1.
    let err = QuadMesh::new(p.clone(), vec![[0, 1, 2, 3], [1, 0, 4, 5], [0, 1, 6, 7]]).unwrap_err();
    assert!(matches!(
        err,
        MeshError::NonManifoldEdge {
            a: 0,
            b: 1,
            first: 0,
            second: 1,
            third: 2
        }
    ));
    let err = QuadMesh::new(p.clone(), vec![[0, 1, 2, 3], [1, 0, 4, 5], [1, 0, 6, 7]]).unwrap_err();
    assert_eq!(
        err,
        MeshError::NonManifoldEdge {
            a: 0,
            b: 1,
            first: 0,
            second: 1,
            third: 2
        }
    );
    // Flipped face.
    let err = QuadMesh::new(p[..6].to_vec(), vec![[0, 1, 2, 3], [0, 1, 4, 5]]).unwrap_err();
    assert_eq!(
        err,
        MeshError::InconsistentOrientation {
            a: 0,
            b: 1,
            first: 0,
            second: 1
        }
    );
    // Bow-tie: two quads touching at vertex 0 only.
    let err = QuadMesh::new(p[..7].to_vec(), vec![[0, 1, 2, 3], [0, 4, 5, 6]]).unwrap_err();
    assert_eq!(err, MeshError::NonManifoldVertex { vertex: 0 });
    let err = QuadMesh::new(p[..5].to_vec(), vec![[0, 1, 2, 3]]).unwrap_err();
    assert_eq!(err, MeshError::UnusedVertex { vertex: 4 });
    let mut bad = p[..4].to_vec();
    bad[2][1] = f64::NAN;
    assert_eq!(
        QuadMesh::new(bad, vec![[0, 1, 2, 3]]).unwrap_err(),
        MeshError::NonFiniteVertex { vertex: 2 }
    );
    // Two cubes sharing one vertex: each fan is closed, but there are two.
    let c = cube();
    let (mut v, mut f) = c.into_parts();
    let offset = v.len() as u32 - 1;
    v.extend((1..8).map(|i| [2.0 + (i & 1) as f64, 0.0, 0.0]));
    // Remap so that vertex 0 of the second cube is vertex 7 of the first.
    let remap = |i: u32| if i == 0 { 7 } else { i + offset };
    let second: Vec<[u32; 4]> = cube().faces().iter().map(|q| q.map(remap)).collect();
    f.extend(second);
    assert_eq!(
        QuadMesh::new(v, f).unwrap_err(),
        MeshError::NonManifoldVertex { vertex: 7 }
    );
}

#[test]
fn mesh_obj_round_trip() {
    let cube = cube();
    let bytes = write_obj(&cube);
    assert_eq!(parse_obj(&bytes).expect("parse"), cube);

    let mut refined = catmull_clark(&m_t()).expect("refine");
    refined = catmull_clark(&refined).expect("refine");
    let back = parse_obj(&write_obj(&refined)).expect("parse");
    assert_eq!(back, refined);
    assert!(back
        .vertices()
        .iter()
        .zip(refined.vertices())
        .all(|(a, b)| a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())));
}

#[test]
fn mesh_obj_parses_slashes_negatives_and_comments() {
    let text = b"# a quad\r\nmtllib x.mtl\no thing\nv 0 0 0\nv 1 0 0 1.0\nv 1 1 0\nv 0 1 0\nvt 0 0\nvn 0 0 1\nf 1/1/1 2//1 3/1 4 # comment\nv 2 0 0\nv 2 1 0\nf -5 -2 -1 -4\n";
    let mesh = parse_obj(text).expect("parse");
    assert_eq!(mesh.faces(), &[[0, 1, 2, 3], [1, 4, 5, 2]]);
    assert_eq!(mesh.vertex_count(), 6);
}

#[test]
fn mesh_obj_rejects_bad_input() {
    let tri = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nf 1 2 3\n";
    assert_eq!(
        parse_obj(tri).unwrap_err(),
        ObjError::NotQuad {
            line: 4,
            corners: 3
        }
    );
    let pent = b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 2 0\nf 1 2 3 4 5\n";
    assert_eq!(
        parse_obj(pent).unwrap_err(),
        ObjError::NotQuad {
            line: 6,
            corners: 5
        }
    );
    let msg = parse_obj(tri).unwrap_err().to_string();
    assert!(msg.contains("line 4"), "{msg}");
    assert_eq!(
        parse_obj(b"v 0 0\n").unwrap_err(),
        ObjError::BadVertex { line: 1 }
    );
    assert!(matches!(
        parse_obj(b"v 0 0 0\nf 1 2 x 4\n").unwrap_err(),
        ObjError::BadIndex { line: 2, .. }
    ));
    assert!(matches!(
        parse_obj(b"v 0 0 0\nf 1 2 0 4\n").unwrap_err(),
        ObjError::BadIndex { line: 2, .. }
    ));
    assert_eq!(
        parse_obj(b"v 0 0 0\nf -1 -2 -3 -4\n").unwrap_err(),
        ObjError::IndexOutOfRange {
            line: 2,
            index: -2,
            vertex_count: 1
        }
    );
    assert_eq!(
        parse_obj(b"v 0 0 0\nf 1 2 3 4\n").unwrap_err(),
        ObjError::IndexOutOfRange {
            line: 2,
            index: 2,
            vertex_count: 1
        }
    );
    assert!(matches!(
        parse_obj(b"v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 2 2 2\nf 1 2 3 4\n").unwrap_err(),
        ObjError::Mesh(MeshError::UnusedVertex { vertex: 4 })
    ));
    assert_eq!(
        parse_obj(b"").unwrap_err(),
        ObjError::Mesh(MeshError::NoFaces)
    );
    assert_eq!(
        parse_obj(b"v 0 0 0\n\xff\n").unwrap_err(),
        ObjError::NotUtf8 { line: 2 }
    );
}

/// The rules of the OBJ parser shared with the triangle-mesh reader.
#[test]
fn mesh_obj_follows_the_shared_parser_rules() {
    let quad = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n";
    // A `w` after x, y, z is legal; any other trailing word is not.
    assert!(parse_obj(quad.replace("v 1 0 0", "v 1 0 0 1").as_bytes()).is_ok());
    assert_eq!(
        parse_obj(quad.replace("v 1 0 0", "v 1 0 0 w").as_bytes()).unwrap_err(),
        ObjError::BadVertex { line: 2 }
    );
    // A non-finite coordinate is refused on its line, before later defects.
    assert!(matches!(
        parse_obj(format!("v 0 nan 0\n{quad}f 1 2 3\n").as_bytes()).unwrap_err(),
        ObjError::NonFiniteVertex {
            line: 1,
            axis: 'y',
            ..
        }
    ));
    // `v` and `f` lines are separated by ASCII whitespace only.
    assert_eq!(
        parse_obj(quad.replace("f 1 2", "f 1\u{a0}2").as_bytes()).unwrap_err(),
        ObjError::NotAsciiSpace {
            line: 5,
            space: '\u{a0}'
        }
    );
    // Every reference of a face is read before its corners are counted.
    assert!(matches!(
        parse_obj(b"v 0 0 0\nf 1 2 x\n").unwrap_err(),
        ObjError::BadIndex { line: 2, .. }
    ));
}

#[test]
fn mesh_catmull_clark_point_rules() {
    let cube = cube();
    let r = catmull_clark(&cube).expect("refine");
    // Valence-3 vertex at the origin: (F + 2R + (n - 3)P) / n with n = 3.
    for k in 0..3 {
        assert!((r.vertices()[0][k] - 2.0 / 9.0).abs() < 1e-15);
    }
    // Inner edge 0-1: average of its ends and the two face points.
    let he = cube.half_edges();
    let e = (0..he.edge_count())
        .find(|&e| {
            let [a, b] = he.edge_vertices(e);
            (a.min(b), a.max(b)) == (0, 1)
        })
        .expect("edge 0-1");
    let p = r.vertices()[8 + e];
    assert!((p[0] - 0.5).abs() < 1e-15);
    assert!((p[1] - 0.125).abs() < 1e-15);
    assert!((p[2] - 0.125).abs() < 1e-15);
    // Face point: centroid of the face.
    assert_eq!(r.vertices()[8 + 12], [0.5, 0.5, 0.0]);

    // Boundary vertex: (a + 6p + b) / 8 along the boundary; boundary edge: midpoint.
    let (mut v, f) = grid(2);
    v[1][2] = 1.0;
    let g = QuadMesh::new(v, f).expect("grid");
    let r = catmull_clark(&g).expect("refine");
    assert_eq!(r.vertices()[1], [1.0, 0.0, 0.75]);
    let he = g.half_edges();
    let e = (0..he.edge_count())
        .find(|&e| he.edge_vertices(e) == [0, 1])
        .expect("edge 0-1");
    assert_eq!(r.vertices()[9 + e], [0.5, 0.0, 0.5]);
    assert_eq!(r.vertices()[0], [0.0, 0.0, 0.0]);
}

fn refined(mesh: QuadMesh, times: usize) -> QuadMesh {
    (0..times).fold(mesh, |m, _| catmull_clark(&m).expect("refine"))
}

#[test]
fn g1_dimension_matches_corollary_1_on_the_papers_meshes() {
    // M_T and its four refinements (Table 1).
    let mut mesh = m_t();
    for expected in [72, 240, 864, 3264, 12672] {
        let domain = G1Domain::new(mesh.clone()).unwrap();
        assert!(!domain.refined);
        assert_eq!(
            domain.dimension().total(),
            expected,
            "{} faces",
            mesh.face_count()
        );
        mesh = refined(mesh, 1);
    }
    // The 96-patch hexagonal mesh (Table 2) and the 96-face sphere (Table 3).
    let hex = refined(hexagon(), 2);
    assert_eq!(hex.face_count(), 96);
    assert_eq!(G1Domain::new(hex).unwrap().dimension().total(), 1725);
    let sphere = refined(cube(), 2);
    assert_eq!(sphere.face_count(), 96);
    assert_eq!(G1Domain::new(sphere).unwrap().dimension().total(), 1512);
}

#[test]
fn g1_dimension_of_a_regular_grid_is_the_c1_biquintic_count() {
    // Without EVs the G1 space is the C1 space: on an n x n grid, biquintic
    // splines with interior knots of multiplicity 4 have 6 + 4 (n - 1) = 4n + 2
    // functions per direction. Corollary 1 counts 4 (V + E + F) = 4 (2n + 1)^2:
    // an independent check of the regular part of the formula.
    for n in 1..6u32 {
        let (v, f) = grid(n);
        let mesh = QuadMesh::new(v, f).unwrap();
        let d = G1Domain::new(mesh).unwrap().dimension();
        assert_eq!(d.total(), ((4 * n + 2) * (4 * n + 2)) as usize, "n = {n}");
    }
}

#[test]
fn adjacent_extraordinary_vertices_are_refined_once() {
    // The cube's EVs are joined by edges: not isolated.
    let domain = G1Domain::new(cube()).unwrap();
    assert!(domain.refined);
    assert_eq!(domain.mesh.face_count(), 24);
    assert!(domain.classification.has_isolated_evs());
}

#[test]
fn a_boundary_ev_counts_its_valence_plus_two() {
    // An L of three unit quads: the inner corner (1, 1) is a boundary EV with
    // four edges (kappa = 3 patches): N + 2 = 6 functions. Five corners and two
    // boundary regular vertices take 4 each; two extraordinary edges 2 each,
    // eight boundary edges 4 each, three faces 4 each: 34 + 36 + 12.
    let domain = G1Domain::new(l_shape()).unwrap();
    let c = &domain.classification;
    assert_eq!((c.n_bev, c.n_c, c.n_brv, c.n_ee, c.n_be), (1, 5, 2, 2, 8));
    let d = domain.dimension();
    assert_eq!((d.vertex, d.edge, d.face), (34, 36, 12));
    assert_eq!(d.total(), 82);
}

/// An L of three unit quads; the inner corner (1, 1) is a boundary EV.
fn l_shape() -> QuadMesh {
    let vertices = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [2.0, 1.0, 0.0],
        [0.0, 2.0, 0.0],
        [1.0, 2.0, 0.0],
    ];
    let faces = vec![[0, 1, 4, 3], [1, 2, 5, 4], [3, 4, 7, 6]];
    QuadMesh::new(vertices, faces).unwrap()
}

/// A half disc split into `kappa` quads around the origin, a boundary EV
/// with kappa patches (N = kappa + 1 edges).
fn half_fan(kappa: usize) -> QuadMesh {
    let step = std::f64::consts::PI / kappa as f64;
    let at = |r: f64, a: f64| [r * a.cos(), r * a.sin(), 0.0];
    // 0 centre, 1..=kappa+1 rim points, then kappa outer points between them.
    let mut vertices = vec![[0.0; 3]];
    vertices.extend((0..=kappa).map(|k| at(1.0, step * k as f64)));
    vertices.extend((0..kappa).map(|k| at(1.3, step * (k as f64 + 0.5))));
    let rim = |k: usize| 1 + k as u32;
    let outer = |k: usize| (kappa + 2 + k) as u32;
    let faces = (0..kappa)
        .map(|k| [0, rim(k), outer(k), rim(k + 1)])
        .collect();
    QuadMesh::new(vertices, faces).unwrap()
}

#[test]
fn boundary_evs_of_any_valence_classify_and_count() {
    for kappa in 3..7 {
        let domain = G1Domain::new(half_fan(kappa)).unwrap();
        let c = &domain.classification;
        assert_eq!(c.vertices[0], VertexKind::BoundaryExtraordinary);
        assert_eq!(c.valences[0], kappa + 1);
        assert_eq!((c.n_bev, c.n_ee), (1, kappa - 1), "kappa {kappa}");
        let basis = G1Basis::new(&domain).unwrap();
        assert_eq!(basis.len(), domain.dimension().total(), "kappa {kappa}");
        let rows = g1_constraints(&domain).unwrap();
        let w: Vec<f64> = (0..basis.len()).map(|k| (k as f64 * 0.37).sin()).collect();
        assert!(defect(&rows, &basis.combine(&w)) < 1e-10, "kappa {kappa}");
    }
}

/// The dimension of the null space of the G1 constraints (eq. 3), by SVD.
fn null_space_dimension(domain: &G1Domain) -> usize {
    let rows = g1_constraints(domain).unwrap();
    let cols = PATCH_COEFFICIENTS * domain.mesh.face_count();
    let mut a = faer::Mat::<f64>::zeros(rows.len().max(1), cols);
    for (r, row) in rows.iter().enumerate() {
        for &(k, w) in row {
            a[(r, k)] += w;
        }
    }
    let s = a.singular_values().unwrap();
    let tol = 1e-9 * s.first().copied().unwrap_or(1.0);
    cols - s.iter().filter(|&&x| x > tol).count()
}

/// Small domains with inner and boundary EVs of several valences, for the
/// checks that need dense linear algebra.
fn test_domains() -> Vec<(&'static str, QuadMesh)> {
    vec![
        ("M_T", m_t()),
        ("M_T refined", refined(m_t(), 1)),
        ("hexagon", hexagon()),
        ("L (boundary EV, kappa 3)", l_shape()),
        ("L refined", refined(l_shape(), 1)),
        ("half fan kappa 4", half_fan(4)),
        ("half fan kappa 5 refined", refined(half_fan(5), 1)),
        ("cube refined", refined(cube(), 1)),
    ]
}

#[test]
fn g1_constraints_have_the_null_space_of_corollary_1() {
    let (v, f) = grid(3);
    let mut meshes = test_domains();
    meshes.push(("grid 3x3", QuadMesh::new(v, f).unwrap()));
    for (name, mesh) in meshes {
        let domain = G1Domain::new(mesh).unwrap();
        assert_eq!(
            null_space_dimension(&domain),
            domain.dimension().total(),
            "{name}"
        );
    }
}

#[test]
fn g1_basis_is_local_independent_and_g1_with_the_dimension_of_corollary_1() {
    let (v, f) = grid(2);
    let mut meshes = test_domains();
    meshes.push(("grid 2x2", QuadMesh::new(v, f).unwrap()));
    for (name, mesh) in meshes {
        let domain = G1Domain::new(mesh).unwrap();
        let basis = G1Basis::new(&domain).unwrap();
        let expected = domain.dimension();
        assert_eq!(basis.len(), expected.total(), "{name}: count");
        let count = |pred: fn(&Feature) -> bool| basis.features.iter().filter(|f| pred(f)).count();
        assert_eq!(
            count(|f| matches!(f, Feature::Face(_))),
            expected.face,
            "{name}: faces"
        );
        assert_eq!(
            count(|f| matches!(f, Feature::Edge(_))),
            expected.edge,
            "{name}: edges"
        );
        assert_eq!(
            count(|f| matches!(f, Feature::Vertex(_))),
            expected.vertex,
            "{name}: vertices"
        );
        // Every function and random combinations satisfy eq. 3.
        let rows = g1_constraints(&domain).unwrap();
        for k in 0..basis.len() {
            let mut w = vec![0.0; basis.len()];
            w[k] = 1.0;
            assert!(
                defect(&rows, &basis.combine(&w)) < 1e-10,
                "{name}: function {k}"
            );
        }
        let mut x = 0.37f64;
        let w: Vec<f64> = (0..basis.len())
            .map(|_| {
                x = (x * 997.0 + 0.123).fract();
                x - 0.5
            })
            .collect();
        assert!(
            defect(&rows, &basis.combine(&w)) < 1e-10,
            "{name}: combination"
        );
        // Independent: the coefficient matrix has full column rank.
        let mut m = faer::Mat::<f64>::zeros(basis.coefficients, basis.len());
        for (j, function) in basis.functions.iter().enumerate() {
            for &(k, value) in function {
                m[(k, j)] = value;
            }
        }
        let s = m.singular_values().unwrap();
        let rank = s.iter().filter(|&&x| x > 1e-9 * s[0]).count();
        assert_eq!(rank, basis.len(), "{name}: independence");
        // Local: a vertex function lives on the faces around its vertex.
        for (function, feature) in basis.functions.iter().zip(&basis.features) {
            if let Feature::Vertex(v) = feature {
                for &(k, _) in function {
                    let face = domain.mesh.faces()[k / PATCH_COEFFICIENTS];
                    assert!(
                        face.contains(&(*v as u32)),
                        "{name}: vertex {v} function leaks"
                    );
                }
            }
        }
    }
}
