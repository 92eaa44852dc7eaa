use super::*;
use crate::proptest_support::{rotation, vec3};
use proptest::prelude::*;
use std::f64::consts::TAU;

fn assert_close(got: Real, expected: Real, rel: Real) {
    let err = (got - expected).abs() / expected.abs();
    assert!(err <= rel, "got {got}, expected {expected}: relative error {err:e} > {rel:e}");
}

/// The cube [0, s]³ moved by `shift`, 12 triangles facing out.
fn cube(s: Real, shift: Vec3) -> (Vec<Vec3>, Vec<[usize; 3]>) {
    let vertices = (0..8)
        .map(|i| {
            Vec3::new((i & 1) as Real, ((i >> 1) & 1) as Real, ((i >> 2) & 1) as Real) * s + shift
        })
        .collect();
    // vertex i = x + 2y + 4z; each face two triangles counterclockwise seen from outside
    let triangles = vec![
        [0, 2, 1],
        [1, 2, 3], // z = 0
        [4, 5, 6],
        [5, 7, 6], // z = 1
        [0, 1, 4],
        [1, 5, 4], // y = 0
        [2, 6, 3],
        [3, 6, 7], // y = 1
        [0, 4, 2],
        [2, 4, 6], // x = 0
        [1, 3, 5],
        [3, 7, 5], // x = 1
    ];
    (vertices, triangles)
}

/// A tube of `around × (along + 1)` vertices: vertex (i, j) = j·around + i at angle 2πi/around
/// about +z, radius `radius(i, j)`, height `height(i, j)`; triangles facing out, split as the
/// PFacet tube builder splits them. Returns its bottom and top loops, in the direction the
/// triangles run along them.
#[derive(Clone, Debug)]
struct Tube {
    vertices: Vec<Vec3>,
    triangles: Vec<[usize; 3]>,
    bottom: Vec<usize>,
    top: Vec<usize>,
}

fn tube(
    around: usize,
    along: usize,
    radius: impl Fn(usize, usize) -> Real,
    height: impl Fn(usize, usize) -> Real,
) -> Tube {
    let node = |i: usize, j: usize| (i % around) + j * around;
    let mut vertices = Vec::new();
    for j in 0..=along {
        for i in 0..around {
            let t = TAU * i as Real / around as Real;
            vertices.push(Vec3::new(radius(i, j) * t.cos(), radius(i, j) * t.sin(), height(i, j)));
        }
    }
    let mut triangles = Vec::new();
    for j in 0..along {
        for i in 0..around {
            triangles.push([node(i, j), node(i + 1, j), node(i, j + 1)]);
            triangles.push([node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)]);
        }
    }
    let bottom = (0..around).map(|i| node(i, 0)).collect();
    let top = (0..around).rev().map(|i| node(i, along)).collect();
    Tube { vertices, triangles, bottom, top }
}

/// Area of the regular polygon of `n` vertices on a circle of radius `r`.
fn polygon_area(n: usize, r: Real) -> Real {
    0.5 * n as Real * r * r * (TAU / n as Real).sin()
}

fn horizontal(z: Real) -> Plane {
    Plane { point: Vec3::new(0.3, -0.2, z), normal: Vec3::z() }
}

#[test]
fn cube_volume_is_its_side_cubed_and_turns_negative_inside_out() {
    for (s, shift) in
        [(1.0, Vec3::zeros()), (0.25, Vec3::new(-3.0, 7.0, 2.0)), (40.0, Vec3::new(1e3, 0.0, -1e3))]
    {
        let (v, mut t) = cube(s, shift);
        assert_close(closed_surface_volume(&v, &t), s * s * s, 1e-14);
        t.iter_mut().for_each(|f| f.swap(1, 2));
        assert_close(closed_surface_volume(&v, &t), -s * s * s, 1e-14);
    }
}

#[test]
fn icosahedron_volume_is_exact() {
    let phi = (1.0 + 5.0_f64.sqrt()) / 2.0;
    let raw = [
        (-1.0, phi, 0.0),
        (1.0, phi, 0.0),
        (-1.0, -phi, 0.0),
        (1.0, -phi, 0.0),
        (0.0, -1.0, phi),
        (0.0, 1.0, phi),
        (0.0, -1.0, -phi),
        (0.0, 1.0, -phi),
        (phi, 0.0, -1.0),
        (phi, 0.0, 1.0),
        (-phi, 0.0, -1.0),
        (-phi, 0.0, 1.0),
    ];
    let triangles = [
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    let shift = Vec3::new(0.5, -1.5, 2.0);
    let vertices: Vec<Vec3> = raw.iter().map(|&(x, y, z)| Vec3::new(x, y, z) + shift).collect();
    // edge 2: V = (5/12)(3 + √5)·a³
    let exact = 5.0 / 12.0 * (3.0 + 5.0_f64.sqrt()) * 8.0;
    assert_close(closed_surface_volume(&vertices, &triangles), exact, 1e-14);
}

#[test]
fn prism_closed_by_its_own_caps_has_area_times_height() {
    let (n, r, h) = (9, 0.7, 2.5);
    let mut t = tube(n, 4, |_, _| r, |_, j| h * j as Real / 4.0);
    // caps as fans from an extra vertex on the axis, facing out
    let (lo, hi) = (t.vertices.len(), t.vertices.len() + 1);
    t.vertices.extend([Vec3::zeros(), Vec3::new(0.0, 0.0, h)]);
    for i in 0..n {
        let (b0, b1) = (t.bottom[i], t.bottom[(i + 1) % n]);
        t.triangles.push([lo, b1, b0]);
        let (t0, t1) = (t.top[i], t.top[(i + 1) % n]);
        t.triangles.push([hi, t1, t0]);
    }
    assert_close(closed_surface_volume(&t.vertices, &t.triangles), polygon_area(n, r) * h, 1e-14);
}

#[test]
fn open_tube_closed_by_two_planes_is_the_prism() {
    let (n, r, h) = (16, 0.1, 0.8);
    let t = tube(n, 20, |_, _| r, |_, j| h * j as Real / 20.0);
    let area = polygon_area(n, r);
    let closed = |z0: Real, z1: Real| {
        let closures = [
            PlaneClosure { boundary: t.bottom.clone(), plane: horizontal(z0) },
            PlaneClosure { boundary: t.top.clone(), plane: horizontal(z1) },
        ];
        volume_closed_by_planes(&t.vertices, &t.triangles, &closures)
    };
    // planes through the end rings, then away from them (the ribbons add straight walls),
    // then inside the tube (the ribbons fold back)
    assert_close(closed(0.0, h), area * h, 1e-13);
    assert_close(closed(-0.3, h + 0.05), area * (h + 0.35), 1e-13);
    assert_close(closed(0.2, h - 0.1), area * (h - 0.3), 1e-13);
    // the sign of a plane's normal does not matter
    let flipped = [
        PlaneClosure {
            boundary: t.bottom.clone(),
            plane: Plane { point: Vec3::zeros(), normal: -Vec3::z() },
        },
        PlaneClosure {
            boundary: t.top.clone(),
            plane: Plane { point: Vec3::new(0.0, 0.0, h), normal: Vec3::z() * 3.0 },
        },
    ];
    assert_close(volume_closed_by_planes(&t.vertices, &t.triangles, &flipped), area * h, 1e-13);
}

#[test]
fn tube_cut_obliquely_and_closed_by_the_cutting_plane() {
    // top ring on the plane z = h − s·x: V = ∫ (h − s·x) dA = area·h (centroid at x = 0)
    let (n, r, h, s) = (12, 0.5, 2.0, 0.6);
    let t = tube(
        n,
        5,
        |_, _| r,
        |i, j| {
            let x = r * (TAU * i as Real / n as Real).cos();
            (h - s * x) * j as Real / 5.0
        },
    );
    let closures = [
        PlaneClosure { boundary: t.bottom.clone(), plane: horizontal(0.0) },
        PlaneClosure {
            boundary: t.top.clone(),
            plane: Plane { point: Vec3::new(0.0, 0.0, h), normal: Vec3::new(s, 0.0, 1.0) },
        },
    ];
    let v = volume_closed_by_planes(&t.vertices, &t.triangles, &closures);
    assert_close(v, polygon_area(n, r) * h, 1e-13);
}

#[test]
fn far_from_the_origin_the_volume_is_the_same_to_round_off() {
    let t = tube(
        10,
        3,
        |i, j| 0.3 + 0.05 * ((i * 7 + j * 3) % 5) as Real,
        |i, j| j as Real * 0.4 + 0.02 * (i % 3) as Real,
    );
    let planes = [
        Plane { point: Vec3::new(0.0, 0.0, -0.1), normal: Vec3::new(0.1, 0.2, -1.0) },
        Plane { point: Vec3::new(0.0, 0.0, 1.3), normal: Vec3::new(-0.2, 0.1, 1.0) },
    ];
    let volume = |shift: Vec3| {
        let vertices: Vec<Vec3> = t.vertices.iter().map(|x| x + shift).collect();
        let closures = [
            PlaneClosure {
                boundary: t.bottom.clone(),
                plane: Plane { point: planes[0].point + shift, ..planes[0] },
            },
            PlaneClosure {
                boundary: t.top.clone(),
                plane: Plane { point: planes[1].point + shift, ..planes[1] },
            },
        ];
        volume_closed_by_planes(&vertices, &t.triangles, &closures)
    };
    let v0 = volume(Vec3::zeros());
    assert!(v0 > 0.0);
    for shift in [Vec3::new(1e3, -2e3, 5e2), Vec3::new(-1e5, 0.0, 3e4)] {
        // round-off of the shifted coordinates: 1e-16 of |shift| over a mesh of size ~1
        let tolerance = 64.0 * Real::EPSILON * shift.norm();
        assert_close(volume(shift), v0, tolerance);
    }
}

#[test]
fn polygon_vector_area_of_a_square() {
    let square = [
        Vec3::new(1.0, 1.0, 5.0),
        Vec3::new(3.0, 1.0, 5.0),
        Vec3::new(3.0, 3.0, 5.0),
        Vec3::new(1.0, 3.0, 5.0),
    ];
    assert!((polygon_vector_area(&square) - Vec3::new(0.0, 0.0, 4.0)).norm() < 1e-15);
    assert_eq!(polygon_vector_area(&[]), Vec3::zeros());
}

/// A wobbly tube (radii and heights perturbed per node) and two tilted closing planes near
/// its ends.
fn wobbly_tube() -> impl Strategy<Value = (Tube, [Plane; 2])> {
    (3usize..12, 1usize..5, any::<u64>(), vec3(0.4), vec3(0.4), -0.3..0.3, -0.3..0.3).prop_map(
        |(around, along, seed, tilt0, tilt1, dz0, dz1): (_, _, u64, Vec3, Vec3, Real, Real)| {
            // a cheap deterministic jitter in [−1, 1] per node from the seed
            let jitter = move |i: usize, j: usize, k: u64| {
                let h = seed
                    .wrapping_add((i as u64 + 1).wrapping_mul(0x9E37_79B9_7F4A_7C15))
                    .wrapping_mul((j as u64 + 7).wrapping_mul(0xBF58_476D_1CE4_E5B9) | 1)
                    .wrapping_add(k.wrapping_mul(0x94D0_49BB_1331_11EB));
                ((h >> 11) as Real / (1u64 << 53) as Real) * 2.0 - 1.0
            };
            let t = tube(
                around,
                along,
                move |i, j| 1.0 + 0.3 * jitter(i, j, 1),
                move |i, j| j as Real + 0.2 * jitter(i, j, 2),
            );
            let top = along as Real;
            let planes = [
                Plane {
                    point: Vec3::new(0.0, 0.0, dz0),
                    normal: Vec3::new(tilt0.x, tilt0.y, -1.0),
                },
                Plane {
                    point: Vec3::new(0.0, 0.0, top + dz1),
                    normal: Vec3::new(tilt1.x, tilt1.y, 1.0),
                },
            ];
            (t, planes)
        },
    )
}

fn closures(t: &Tube, planes: &[Plane; 2]) -> [PlaneClosure; 2] {
    [
        PlaneClosure { boundary: t.bottom.clone(), plane: planes[0] },
        PlaneClosure { boundary: t.top.clone(), plane: planes[1] },
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Moved and turned as a whole, the closed tube keeps its volume.
    #[test]
    fn volume_is_invariant_under_rigid_motions(
        (t, planes) in wobbly_tube(),
        rot in rotation(),
        shift in vec3(50.0),
    ) {
        let v0 = volume_closed_by_planes(&t.vertices, &t.triangles, &closures(&t, &planes));
        let moved: Vec<Vec3> = t.vertices.iter().map(|x| rot * x + shift).collect();
        let moved_planes =
            planes.map(|p| Plane { point: rot * p.point + shift, normal: rot * p.normal });
        let v1 = volume_closed_by_planes(&moved, &t.triangles, &closures(&t, &moved_planes));
        // round-off of coordinates up to |shift| + 5 over a closed surface of size ~5
        let tolerance = 1e-13 * (1.0 + v0.abs()) * (5.0 + shift.norm());
        prop_assert!((v1 - v0).abs() <= tolerance, "{} vs {}", v1, v0);
    }

    /// The triangles, ribbons and caps make a closed surface wherever the boundary nodes
    /// are: the flux of (x − o)/3 through it does not depend on the point o.
    #[test]
    fn the_closed_surface_is_watertight((t, planes) in wobbly_tube(), o in vec3(20.0)) {
        let v0 = volume_closed_by_planes(&t.vertices, &t.triangles, &closures(&t, &planes));
        let caps: Real =
            closures(&t, &planes).iter().map(|c| plane_closure_flux(&o, &t.vertices, c)).sum();
        let v1 = triangles_flux(&o, &t.vertices, &t.triangles) + caps;
        // terms of size |o|³ cancel: round-off relative to them
        let tolerance = 1e-13 * (1.0 + v0.abs()) * (5.0 + o.norm()).powi(3);
        prop_assert!((v1 - v0).abs() <= tolerance, "{} vs {}", v1, v0);
    }

    /// Sliding a closing plane by δ along its unit normal adds the prism of its cap:
    /// ΔV = δ·(n̂·A_cap), A_cap the vector area of the cap as it faces out of the closed
    /// surface (the projected loop run backwards) — whichever side the loop's nodes are on.
    #[test]
    fn sliding_a_plane_adds_the_prism_of_its_cap(
        (t, planes) in wobbly_tube(),
        delta in -0.5..0.5_f64,
        which in 0usize..2,
    ) {
        let v0 = volume_closed_by_planes(&t.vertices, &t.triangles, &closures(&t, &planes));
        let n = planes[which].normal.normalize();
        let mut slid = planes;
        slid[which].point += n * delta;
        let v1 = volume_closed_by_planes(&t.vertices, &t.triangles, &closures(&t, &slid));
        let boundary = if which == 0 { &t.bottom } else { &t.top };
        let cap: Vec<Vec3> =
            boundary.iter().rev().map(|&i| planes[which].project(&t.vertices[i])).collect();
        let expected = delta * n.dot(&polygon_vector_area(&cap));
        let error = (v1 - v0 - expected).abs();
        prop_assert!(error <= 1e-12 * (1.0 + v0.abs()), "{} vs {}", v1 - v0, expected);
    }

    /// Scaling every length by k scales the volume by k³.
    #[test]
    fn volume_scales_with_the_cube_of_lengths(
        (t, planes) in wobbly_tube(),
        k in 0.01..100.0_f64,
    ) {
        let v0 = volume_closed_by_planes(&t.vertices, &t.triangles, &closures(&t, &planes));
        let scaled: Vec<Vec3> = t.vertices.iter().map(|x| x * k).collect();
        let scaled_planes = planes.map(|p| Plane { point: p.point * k, normal: p.normal });
        let v1 = volume_closed_by_planes(&scaled, &t.triangles, &closures(&t, &scaled_planes));
        let unscaled = v1 / (k * k * k);
        prop_assert!((unscaled - v0).abs() <= 1e-12 * (1.0 + v0.abs()), "{} vs {}", unscaled, v0);
    }
}
