//! The curvature verdict at boundary, crease and corner vertices is made on
//! the sector's radius-3 second-order matrix (math doc section 18.5), not on
//! the local matrix: `mu` is the largest modulus after the subdominant pair
//! of that matrix's spectrum, which holds eigenvalues the local matrix has
//! not (the regular part of the ring of patches).

use subdiv_lab::boundary::analysis::analyze_sector;
use subdiv_lab::boundary::charmap::refinement_matrix;
use subdiv_lab::boundary::{RuleSet, SectorConfig, VertexKind};
use subdiv_lab::mesh::sharp::rules::SdcScheme;
use subdiv_lab::spectral::{Eigen, EigenOptions};

/// `mu` of every configuration is `|e_3|` of the spectrum of the radius-3
/// grid matrix, `1 + 3 E + 9 F` points for Catmull-Clark and `1 + 3 E + 3 F`
/// for Loop (`E` edges, `F` faces at the vertex).
#[test]
fn mu_comes_from_the_radius_3_sector_matrix() {
    for scheme in [SdcScheme::CatmullClark, SdcScheme::Loop] {
        for rules in [RuleSet::Standard, RuleSet::Blz] {
            for k in 1..=5 {
                for (kind, faces, angle) in [
                    (VertexKind::Boundary, vec![k], None),
                    (VertexKind::Crease, vec![k, k + 1], None),
                    (VertexKind::Corner, vec![k], Some(90.0)),
                    (VertexKind::Corner, vec![k], Some(250.0)),
                ] {
                    let c = SectorConfig::new(scheme, kind, &faces, angle, rules).unwrap();
                    let m = refinement_matrix(&c, 3, 3).unwrap();
                    let (e, f) = (c.edge_count(), c.face_count());
                    let inner = if scheme == SdcScheme::CatmullClark {
                        9
                    } else {
                        3
                    };
                    assert_eq!(m.nrows(), 1 + 3 * e + inner * f, "{c}");
                    let values = Eigen::new(&m, EigenOptions::VALUES).unwrap();
                    let mu = values.values()[3].norm();
                    let cv = analyze_sector(&c).unwrap().curvature;
                    assert!(
                        (cv.mu - mu).abs() <= 1e-9,
                        "{c}: curvature mu {} but the radius-3 matrix gives {mu}",
                        cv.mu
                    );
                }
            }
        }
    }
}

/// Loop's corner of one face: the local matrix (`v, e_0, e_1`) has only the
/// eigenvalues `1, 1/2, 1/2`; the ring's regular part brings `mu = 1/8`
/// (three times: the cubic B-spline's), so the curvature is certified
/// `zero` (`mu / lambda^2 = 1/2`).
#[test]
fn loop_corner_of_one_face_has_its_mu_in_the_regular_part() {
    for rules in [RuleSet::Standard, RuleSet::Blz] {
        let c = SectorConfig::new(SdcScheme::Loop, VertexKind::Corner, &[1], Some(90.0), rules)
            .unwrap();
        assert_eq!(c.local_matrix().unwrap().matrix().nrows(), 3);
        let cv = analyze_sector(&c).unwrap().curvature;
        assert!((cv.mu - 0.125).abs() < 1e-12, "{}", cv.mu);
        assert!(cv.mu_regular_part);
        assert_eq!(cv.mu_multiplicity, 3);
        assert_eq!(cv.verdict.as_str(), "zero", "{}", cv.reason);
    }
}
