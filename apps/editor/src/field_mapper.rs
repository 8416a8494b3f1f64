//! [`FieldMapper`]: the map from reduced coefficients to the `f32` field the page draws,
//! `x = U v`, with a cache that makes dragging one constraint cost `O(F)` instead of `O(F d)`.
//!
//! The spline is linear in the prescribed values: `x(c) = Σ_i c_i x̂_i` with "cardinal" fields
//! `x̂_i` that depend only on the constraint rows. While one constraint `j` changes only its
//! values (a drag), `x(c) = x(c⁰) + Σ_k (c_jk − c⁰_jk) x̂_jk`. On the first value change of `j`
//! the mapper streams `U` once for `x(c⁰)` and the (one or two) `x̂_jk` together; every further
//! change of `j` is a sum of at most three vectors of length `n1`. Any other edit invalidates
//! the cache. The reduced coefficients `v` stay exact (the session solves every time), so the
//! full-precision check and the `f32` field agree to `f32` rounding.

use rayon::prelude::*;
use tvf_design::{DesignError, ReducedBasis, ReducedBasisF32, SplineSession};

/// Rows of `U` per parallel task.
const ROWS_PER_TASK: usize = 1024;

/// The value-change cache of one constraint.
struct DragCache {
    id: String,
    base_values: Vec<f64>,
    base_field: Vec<f32>,
    cardinal: Vec<Vec<f32>>,
}

/// `U` in single precision, row-major (`n1 × d`), with the drag cache.
pub(crate) struct FieldMapper {
    fields: ReducedBasisF32,
    d: usize,
    cache: Option<DragCache>,
}

impl FieldMapper {
    /// An `f32` copy of `basis` (row-major, [`ReducedBasis::to_f32`]: of a basis file read on
    /// demand, formed in one pass over the file).
    pub(crate) fn new(basis: &ReducedBasis) -> Result<Self, DesignError> {
        let fields = basis.to_f32()?;
        let d = fields.len();
        Ok(Self {
            fields,
            d,
            cache: None,
        })
    }

    /// `field = U v` (one pass over `U`); forgets the drag cache.
    pub(crate) fn map(&mut self, v: &[f64], field: &mut [f32]) {
        self.cache = None;
        let v32: Vec<f32> = v.iter().map(|&x| x as f32).collect();
        self.map_many(&[&v32], &mut [field]);
    }

    /// The field after constraint `id` took the values `values` (only its values changed since
    /// the last edit; `v` is the session's new solution). Uses the cache if it is for `id`,
    /// otherwise builds it with one pass over `U`. Returns whether the cache was hit.
    pub(crate) fn update_values(
        &mut self,
        session: &mut SplineSession,
        id: &str,
        values: &[f64],
        v: &[f64],
        field: &mut [f32],
    ) -> Result<bool, DesignError> {
        if let Some(cache) = self.cache.as_ref().filter(|c| c.id == id) {
            field.copy_from_slice(&cache.base_field);
            for ((value, base), cardinal) in
                values.iter().zip(&cache.base_values).zip(&cache.cardinal)
            {
                let step = (value - base) as f32;
                if step != 0.0 {
                    field
                        .par_iter_mut()
                        .zip(cardinal.par_iter())
                        .for_each(|(x, c)| *x += step * c);
                }
            }
            return Ok(true);
        }
        // Cardinal coefficients by linearity: v(c + e_k) − v(c), then restore the values.
        let mut cardinal_coefficients = Vec::with_capacity(values.len());
        for k in 0..values.len() {
            let mut shifted = values.to_vec();
            shifted[k] += 1.0;
            session.set_values(id, &shifted)?;
            let vk = session.solve();
            cardinal_coefficients.push(
                vk.iter()
                    .zip(v)
                    .map(|(a, b)| (a - b) as f32)
                    .collect::<Vec<f32>>(),
            );
        }
        session.set_values(id, values)?;
        let v32: Vec<f32> = v.iter().map(|&x| x as f32).collect();
        let n = field.len();
        let mut cardinal = vec![vec![0.0f32; n]; values.len()];
        {
            let mut inputs: Vec<&[f32]> = vec![&v32];
            inputs.extend(cardinal_coefficients.iter().map(Vec::as_slice));
            let mut outputs: Vec<&mut [f32]> = vec![field];
            outputs.extend(cardinal.iter_mut().map(Vec::as_mut_slice));
            self.map_many(&inputs, &mut outputs);
        }
        self.cache = Some(DragCache {
            id: id.to_string(),
            base_values: values.to_vec(),
            base_field: field.to_vec(),
            cardinal,
        });
        Ok(false)
    }

    /// `outputs[i] = U inputs[i]` in one pass over `U` (up to three vectors at a time).
    fn map_many(&self, inputs: &[&[f32]], outputs: &mut [&mut [f32]]) {
        for (ins, outs) in inputs.chunks(3).zip(outputs.chunks_mut(3)) {
            match ins.len() {
                1 => self.map_k::<1>([ins[0]], outs),
                2 => self.map_k::<2>([ins[0], ins[1]], outs),
                _ => self.map_k::<3>([ins[0], ins[1], ins[2]], outs),
            }
        }
    }

    fn map_k<const K: usize>(&self, inputs: [&[f32]; K], outputs: &mut [&mut [f32]]) {
        let d = self.d.max(1);
        let n = outputs.first().map_or(0, |o| o.len());
        let mut results = vec![[0.0f32; K]; n];
        results
            .par_chunks_mut(ROWS_PER_TASK)
            .zip(self.fields.values().par_chunks(ROWS_PER_TASK * d))
            .for_each(|(out, block)| {
                for (o, row) in out.iter_mut().zip(block.chunks_exact(d)) {
                    *o = dot_k(row, &inputs);
                }
            });
        for (r, values) in results.iter().enumerate() {
            for (k, out) in outputs.iter_mut().enumerate() {
                out[r] = values[k];
            }
        }
    }
}

/// `K` dot products of `row` with `inputs[k]`, eight lanes at a time (vectorises).
fn dot_k<const K: usize>(row: &[f32], inputs: &[&[f32]; K]) -> [f32; K] {
    let mut lanes = [[0.0f32; 8]; K];
    let whole = row.len() / 8 * 8;
    for start in (0..whole).step_by(8) {
        let u = &row[start..start + 8];
        for (acc, input) in lanes.iter_mut().zip(inputs) {
            let v = &input[start..start + 8];
            for l in 0..8 {
                acc[l] += u[l] * v[l];
            }
        }
    }
    let mut out = [0.0f32; K];
    for (k, (acc, input)) in lanes.iter().zip(inputs).enumerate() {
        out[k] = acc.iter().sum::<f32>()
            + row[whole..]
                .iter()
                .zip(&input[whole..])
                .map(|(a, b)| a * b)
                .sum::<f32>();
    }
    out
}
