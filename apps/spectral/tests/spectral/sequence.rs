//! Sequences: many frames with one basis, in parallel, give the same frames as one at a time.

use tvf_core::discretization::{HodgeComplex, HodgeOperators};
use tvf_core::generate::torus;
use tvf_discretizations::{Conforming, MassLumping};
use tvf_spectral::{
    basis_id, compress_with_report, compute_basis, relative_l2_error, BasisRequest,
    CoefficientCoding, CompressedFields, FieldCodec,
};

/// A time-dependent field: a rotating swirl around an axis, one frame per time step (3D vectors
/// projected onto the faces).
fn frames<H: HodgeComplex + ?Sized>(
    complex: &H,
    mesh: &tvf_core::TriangleMesh,
    count: usize,
) -> Vec<Vec<f64>> {
    (0..count)
        .map(|k| {
            let angle = 0.3 * k as f64;
            let axis = [angle.cos(), angle.sin(), 0.4];
            let vectors: Vec<[f64; 3]> = mesh
                .faces()
                .iter()
                .map(|f| {
                    let p = mesh.positions();
                    let c: [f64; 3] =
                        std::array::from_fn(|i| (p[f[0]][i] + p[f[1]][i] + p[f[2]][i]) / 3.0);
                    let wave = (3.0 * c[0] + k as f64 * 0.2).sin();
                    [
                        axis[1] * c[2] - axis[2] * c[1] + wave,
                        axis[2] * c[0] - axis[0] * c[2],
                        axis[0] * c[1] - axis[1] * c[0],
                    ]
                })
                .collect();
            complex
                .require_sampling()
                .unwrap()
                .from_face_vectors(&vectors)
                .unwrap()
                .field
        })
        .collect()
}

#[test]
fn a_sequence_compresses_like_its_frames_one_by_one() {
    let mesh = torus(1.0, 0.45, 16, 10).unwrap();
    let complex = Conforming::new(&mesh, MassLumping::Barycentric).unwrap();
    let basis = compute_basis(&complex, &BasisRequest::pairs(60)).unwrap();
    let id = basis_id(&basis);
    let fields = frames(&complex, &mesh, 12);
    for coding in [
        CoefficientCoding::Float64,
        CoefficientCoding::Quantized { bits: 12 },
    ] {
        let codec = FieldCodec::new(&basis, 77, id, 60, coding).unwrap();
        let (file, report) =
            compress_with_report(&codec, basis.field_mass(), &fields, mesh.vertex_count()).unwrap();
        assert_eq!(report.frames, 12);
        assert_eq!(report.bytes, file.to_bytes().len());
        let parsed = CompressedFields::from_bytes(&file.to_bytes()).unwrap();
        let decoded = FieldCodec::for_file(&basis, 77, id, &parsed.header)
            .unwrap()
            .decompress(&parsed)
            .unwrap();
        assert_eq!(decoded.len(), fields.len());
        for (k, field) in fields.iter().enumerate() {
            let single = codec.encode(field).unwrap();
            assert_eq!(
                single, file.frames[k],
                "frame {k} differs from its single compression"
            );
            let error = relative_l2_error(basis.field_mass(), field, &decoded[k]);
            assert_eq!(error, report.relative_errors[k]);
            assert!(error < 0.5, "frame {k}: relative error {error}");
        }
        assert!(report.worst_error() >= report.mean_error());
        let mean = report.relative_errors.iter().sum::<f64>() / 12.0;
        assert!((report.mean_error() - mean).abs() < 1e-15);
        // Against two doubles per face the rate is large, since 2·60+2 ≪ 2F coefficients.
        assert!(
            report.rate_against_two_doubles() > 2.0,
            "{}",
            report.rate_against_two_doubles()
        );
    }
}
