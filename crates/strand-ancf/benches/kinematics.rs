//! Cost of the element kinematics at one integration point and of a whole element's force
//! and tangent (5 Gauss points), planar and spatial.

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use nalgebra::Vector3;
use strand_ancf::planar::{self, PlanarCoords, PlanarPoint, PlanarSection};
use strand_ancf::spatial::{self, SectionFrame, SpatialCoords, SpatialPoint, SpatialSection};
use strand_ancf::{ShapeRow, element_quadrature};

fn planar_q(l: f64) -> PlanarCoords {
    PlanarCoords::from_column_slice(&[0.0, 0.0, 0.98, -0.2, l, -0.1 * l, 0.9, -0.35])
}

fn spatial_q(l: f64) -> SpatialCoords {
    SpatialCoords::from_column_slice(&[
        0.0,
        0.0,
        0.0,
        0.98,
        -0.2,
        0.05,
        l,
        -0.1 * l,
        0.02,
        0.9,
        -0.35,
        0.1,
    ])
}

fn bench(c: &mut Criterion) {
    let l = 0.05;
    let row = ShapeRow::new(0.3 * l, l);
    let qp = planar_q(l);
    let qs = spatial_q(l);
    let frame = SectionFrame::along(Vector3::x()).unwrap();
    let gauss = element_quadrature(l, 5).unwrap();
    let ps = PlanarSection {
        n: 1.0,
        dn_deps: 4.5e3,
        m: 1e-3,
        dm_dkappa: 1.5e-3,
        dm_deps: 1e-4,
    };
    let ss = SpatialSection {
        n: 1.0,
        dn_deps: 4.5e3,
        m: [2e-4, 1e-3],
        dm_dkappa: [[1.5e-3, 1e-4], [1e-4, 1.2e-3]],
        dm_deps: [1e-5, 1e-4],
    };

    c.bench_function("planar point: first", |b| {
        b.iter(|| PlanarPoint::at(black_box(&qp), &row).first().unwrap())
    });
    c.bench_function("planar point: second", |b| {
        b.iter(|| PlanarPoint::at(black_box(&qp), &row).second().unwrap())
    });
    c.bench_function("planar point: second + scatter 8x8", |b| {
        b.iter(|| {
            let s = PlanarPoint::at(black_box(&qp), &row).second().unwrap();
            planar::scatter_hessian(&row, &s.tangent(&ps))
        })
    });
    c.bench_function("spatial point: first", |b| {
        b.iter(|| {
            SpatialPoint::at(black_box(&qs), &row)
                .first(&frame)
                .unwrap()
        })
    });
    c.bench_function("spatial point: second", |b| {
        b.iter(|| {
            SpatialPoint::at(black_box(&qs), &row)
                .second(&frame)
                .unwrap()
        })
    });
    c.bench_function("spatial point: second + scatter 12x12", |b| {
        b.iter(|| {
            let s = SpatialPoint::at(black_box(&qs), &row)
                .second(&frame)
                .unwrap();
            spatial::scatter_hessian(&row, &s.tangent(&ss))
        })
    });
    c.bench_function("planar element (5 Gauss): force + tangent", |b| {
        b.iter(|| {
            let mut f = planar::PlanarVector::zeros();
            let mut k = planar::PlanarMatrix::zeros();
            for p in &gauss {
                let s = PlanarPoint::at(black_box(&qp), &p.row).second().unwrap();
                planar::add_gradient(&mut f, p.weight, &p.row, &s.force(&ps));
                planar::add_hessian(&mut k, p.weight, &p.row, &s.tangent(&ps));
            }
            (f, k)
        })
    });
    c.bench_function("spatial element (5 Gauss): force + tangent", |b| {
        b.iter(|| {
            let mut f = spatial::SpatialVector::zeros();
            let mut k = spatial::SpatialMatrix::zeros();
            for p in &gauss {
                let s = SpatialPoint::at(black_box(&qs), &p.row)
                    .second(&frame)
                    .unwrap();
                spatial::add_gradient(&mut f, p.weight, &p.row, &s.force(&ss));
                spatial::add_hessian(&mut k, p.weight, &p.row, &s.tangent(&ss));
            }
            (f, k)
        })
    });
    c.bench_function("spatial element (5 Gauss): force only", |b| {
        b.iter(|| {
            let mut f = spatial::SpatialVector::zeros();
            for p in &gauss {
                let s = SpatialPoint::at(black_box(&qs), &p.row)
                    .first(&frame)
                    .unwrap();
                spatial::add_gradient(&mut f, p.weight, &p.row, &s.force(&ss));
            }
            f
        })
    });
}

criterion_group!(benches, bench);
criterion_main!(benches);
