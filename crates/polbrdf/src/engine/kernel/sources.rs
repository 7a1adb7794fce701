//! The kernel's inputs: angles by index, direction vectors, angle variables, prepared
//! geometry — the geometry part of a block, computed or prepared, and each source's
//! one-geometry path.

use super::index::IndexSource;
use super::{Kernel, BLOCK};
use crate::engine::block::{self, AngleNeeds, BlockIn, Geom, GeomScratch, Lanes, Thresholds};
use crate::engine::simd::SimdLevel;
use crate::geometry::angles::{self, Trig};
use crate::geometry::batch::{angles_valid, vectors_valid};
use crate::geometry::{AngleVariables, DirectionBatch, Geometry, GeometryBatch};
use crate::model::Evaluation;
use crate::numeric::math::Math;

// -------------------------------------------------------------------------------------------
// Inputs: angles by index; the geometry part of a block, computed or prepared.

/// Validated angles (θi, φi, θr, φr) in radians, by index.
pub(super) trait Source {
    fn get(&self, i: usize) -> [f64; 4];

    /// Elements `start .. start + N` into `b`.
    #[inline(always)]
    fn load_block<const N: usize>(&self, start: usize, b: &mut BlockIn<N>) {
        for j in 0..N {
            [b.ti[j], b.pi[j], b.tr[j], b.pr[j]] = self.get(start + j);
        }
    }
}

pub(super) struct BatchSource<'a> {
    pub(super) cols: [&'a [f64]; 4],
}

impl<'a> BatchSource<'a> {
    pub(super) fn new(batch: &GeometryBatch<'a>, start: usize, len: usize) -> Self {
        let cols = batch.columns();
        assert!(
            start.checked_add(len).is_some_and(|end| end <= batch.len()),
            "range {start}..{start}+{len} beyond a batch of {}",
            batch.len()
        );
        Self {
            cols: cols.map(|c| &c[start..start + len]),
        }
    }
}

impl Source for BatchSource<'_> {
    #[inline(always)]
    fn get(&self, i: usize) -> [f64; 4] {
        [
            self.cols[0][i],
            self.cols[1][i],
            self.cols[2][i],
            self.cols[3][i],
        ]
    }

    #[inline(always)]
    fn load_block<const N: usize>(&self, start: usize, b: &mut BlockIn<N>) {
        let r = start..start + N;
        b.ti.copy_from_slice(&self.cols[0][r.clone()]);
        b.pi.copy_from_slice(&self.cols[1][r.clone()]);
        b.tr.copy_from_slice(&self.cols[2][r.clone()]);
        b.pr.copy_from_slice(&self.cols[3][r]);
    }
}

impl Source for &[Geometry] {
    #[inline(always)]
    fn get(&self, i: usize) -> [f64; 4] {
        let g = &self[i];
        [g.theta_i(), g.phi_i(), g.theta_r(), g.phi_r()]
    }
}

/// Elements `start .. start + len` (len ≤ N) of `src` into `b`; the rest of the block repeats
/// element `start` (valid input, results discarded).
#[inline(always)]
pub(super) fn load<S: Source, const N: usize>(
    src: &S,
    start: usize,
    len: usize,
    b: &mut BlockIn<N>,
) {
    if len == N {
        src.load_block(start, b);
    } else {
        for j in 0..N {
            [b.ti[j], b.pi[j], b.tr[j], b.pr[j]] = src.get(start + if j < len { j } else { 0 });
        }
    }
    for j in 0..N {
        // `+ 0.0` turns −0.0 into +0.0, as `Geometry` does.
        b.ti[j] += 0.0;
        b.tr[j] += 0.0;
    }
}

/// Where the geometry part of each block comes from, and the one-geometry path of an element.
pub(super) trait Blocks {
    /// The geometry part of elements `start .. start + len` (len ≤ N), the optional angles
    /// where `needs` says:
    /// computed in `scratch` (and returned from there) or taken from where it was prepared.
    fn geometry<'s, M: Math, const N: usize, const PAIRS: bool>(
        &'s self,
        start: usize,
        len: usize,
        needs: AngleNeeds,
        scratch: &'s mut GeomScratch<N, M::F>,
    ) -> &'s Geom<N, M::F>
    where
        M::F: Thresholds;

    /// Element `i` by the one-geometry path.
    fn reference(&self, k: &Kernel<'_>, index: IndexSource<'_>, i: usize) -> Evaluation;

    /// Whether elements `start .. start + len` are valid input: always for a validated
    /// source; a [`Checked`] one tests them (the job stops at a block that fails).
    #[inline(always)]
    fn valid(&self, _start: usize, _len: usize) -> bool {
        true
    }
}

/// A source whose elements can be validated a block at a time, as the batch's constructor
/// validates them ([`crate::geometry::Unvalidated`]).
pub(super) trait Validate {
    /// Whether elements `start .. start + len` pass the batch constructor's validation.
    fn check(&self, start: usize, len: usize) -> bool;
}

impl Validate for Computed<BatchSource<'_>> {
    #[inline(always)]
    fn check(&self, start: usize, len: usize) -> bool {
        let r = start..start + len;
        angles_valid(self.0.cols.map(|c| &c[r.clone()]))
    }
}

impl Validate for Directions<'_> {
    #[inline(always)]
    fn check(&self, start: usize, len: usize) -> bool {
        let r = start..start + len;
        vectors_valid(&self.w_i[r.clone()]) & vectors_valid(&self.w_r[r])
    }
}

/// A source not validated ahead: the jobs test each block as they read it ([`Blocks::valid`],
/// the same test as the batch constructors', branch-free over the block, one branch per block)
/// and stop at the first that fails. Otherwise `G` as it is.
pub(super) struct Checked<G>(pub(super) G);

impl<G: Blocks + Validate> Blocks for Checked<G> {
    #[inline(always)]
    fn geometry<'s, M: Math, const N: usize, const PAIRS: bool>(
        &'s self,
        start: usize,
        len: usize,
        needs: AngleNeeds,
        scratch: &'s mut GeomScratch<N, M::F>,
    ) -> &'s Geom<N, M::F>
    where
        M::F: Thresholds,
    {
        self.0.geometry::<M, N, PAIRS>(start, len, needs, scratch)
    }

    fn reference(&self, k: &Kernel<'_>, index: IndexSource<'_>, i: usize) -> Evaluation {
        self.0.reference(k, index, i)
    }

    #[inline(always)]
    fn valid(&self, start: usize, len: usize) -> bool {
        self.0.check(start, len)
    }
}

impl<G: F32Blocks + Validate> F32Blocks for Checked<G> {
    #[inline(always)]
    fn lane_input<const N: usize>(scratch: &GeomScratch<N, f32>, j: usize) -> [f64; 6] {
        G::lane_input::<N>(scratch, j)
    }

    #[inline(always)]
    fn theta_n_f64<M: Math<F = f64>>(x: [f64; 6]) -> f64 {
        G::theta_n_f64::<M>(x)
    }

    #[inline(always)]
    fn gathered_geometry<M: Math<F = f64>, const N: usize>(
        &self,
        pos: &[usize],
        needs: AngleNeeds,
        scratch: &mut GeomScratch<N>,
    ) {
        self.0.gathered_geometry::<M, N>(pos, needs, scratch);
    }
}

/// Geometries whose geometry stages the kernel computes.
pub(super) struct Computed<S>(pub(super) S);

impl<S: Source> Blocks for Computed<S> {
    #[inline(always)]
    fn geometry<'s, M: Math, const N: usize, const PAIRS: bool>(
        &'s self,
        start: usize,
        len: usize,
        needs: AngleNeeds,
        scratch: &'s mut GeomScratch<N, M::F>,
    ) -> &'s Geom<N, M::F>
    where
        M::F: Thresholds,
    {
        load::<S, N>(&self.0, start, len, &mut scratch.input);
        block::geometry::<M, N, PAIRS>(scratch, needs);
        &scratch.geo
    }

    fn reference(&self, k: &Kernel<'_>, index: IndexSource<'_>, i: usize) -> Evaluation {
        let [ti, pi, tr, pr] = self.0.get(i);
        one_geometry(
            k,
            index,
            i,
            Geometry::new_unchecked(ti + 0.0, pi, tr + 0.0, pr),
        )
    }
}

/// Element `i` (at geometry `g`) by the one-geometry path, with its index.
pub(super) fn one_geometry(
    k: &Kernel<'_>,
    index: IndexSource<'_>,
    i: usize,
    g: Geometry,
) -> Evaluation {
    index
        .get(i, k.material)
        .map_or_else(Evaluation::undefined, |n| {
            k.material.evaluate_with_index(&g, n)
        })
}

/// What the single-precision job needs of a source beyond [`Blocks`]: θN in f64 for D's
/// refinement, and the f64 geometry of gathered elements.
pub(super) trait F32Blocks: Blocks {
    /// The f64 input of lane `j` of the block whose f32 geometry `scratch` holds (angles, or
    /// the two vectors), for [`F32Blocks::theta_n_f64`].
    fn lane_input<const N: usize>(scratch: &GeomScratch<N, f32>, j: usize) -> [f64; 6];

    /// θN (rad) in f64 (backend `M`) of one element's [`F32Blocks::lane_input`].
    fn theta_n_f64<M: Math<F = f64>>(x: [f64; 6]) -> f64;

    /// The f64 geometry stages of the elements at positions `pos` (at most N; the rest of the
    /// block repeats the first) into `scratch`.
    fn gathered_geometry<M: Math<F = f64>, const N: usize>(
        &self,
        pos: &[usize],
        needs: AngleNeeds,
        scratch: &mut GeomScratch<N>,
    );
}

impl<S: Source> F32Blocks for Computed<S> {
    #[inline(always)]
    fn lane_input<const N: usize>(scratch: &GeomScratch<N, f32>, j: usize) -> [f64; 6] {
        let b = &scratch.input;
        [b.ti[j], b.pi[j], b.tr[j], b.pr[j], 0.0, 0.0]
    }

    #[inline(always)]
    fn theta_n_f64<M: Math<F = f64>>(x: [f64; 6]) -> f64 {
        // As the f64 path computes it: the reduction, the four sine/cosine pairs, the half
        // vector and one arctangent, from the block's f64 angles.
        let t = Trig::<f64>::new::<M>(x[0], x[1], x[2], x[3]);
        angles::theta_n::<M>(&angles::half_vector::<M>(&t))
    }

    #[inline(always)]
    fn gathered_geometry<M: Math<F = f64>, const N: usize>(
        &self,
        pos: &[usize],
        needs: AngleNeeds,
        scratch: &mut GeomScratch<N>,
    ) {
        let src = Gathered { src: &self.0, pos };
        load::<_, N>(&src, 0, pos.len(), &mut scratch.input);
        block::geometry::<M, N, true>(scratch, needs);
    }
}

/// Direction vectors (the direction entry point, [`DirectionBatch`]) of elements
/// `start .. start + len` of a batch.
pub(super) struct Directions<'a> {
    w_i: &'a [[f64; 3]],
    w_r: &'a [[f64; 3]],
}

impl<'a> Directions<'a> {
    pub(super) fn new(batch: &DirectionBatch<'a>, start: usize, len: usize) -> Self {
        assert!(
            start.checked_add(len).is_some_and(|end| end <= batch.len()),
            "range {start}..{start}+{len} beyond a batch of {}",
            batch.len()
        );
        let (w_i, w_r) = batch.directions();
        Self {
            w_i: &w_i[start..start + len],
            w_r: &w_r[start..start + len],
        }
    }

    /// The vectors of elements `pos(0) .. pos(N − 1)` into `dirs` (structure of arrays).
    #[inline(always)]
    fn load<const N: usize>(&self, pos: impl Fn(usize) -> usize, dirs: &mut [Lanes<N>; 6]) {
        for j in 0..N {
            let (a, b) = (self.w_i[pos(j)], self.w_r[pos(j)]);
            [dirs[0][j], dirs[1][j], dirs[2][j]] = a;
            [dirs[3][j], dirs[4][j], dirs[5][j]] = b;
        }
    }
}

impl Blocks for Directions<'_> {
    #[inline(always)]
    fn geometry<'s, M: Math, const N: usize, const PAIRS: bool>(
        &'s self,
        start: usize,
        len: usize,
        needs: AngleNeeds,
        scratch: &'s mut GeomScratch<N, M::F>,
    ) -> &'s Geom<N, M::F>
    where
        M::F: Thresholds,
    {
        self.load::<N>(|j| start + if j < len { j } else { 0 }, &mut scratch.dirs);
        block::geometry_of_directions::<M, N, PAIRS>(scratch, needs);
        &scratch.geo
    }

    fn reference(&self, k: &Kernel<'_>, index: IndexSource<'_>, i: usize) -> Evaluation {
        let (ti, pi) = angles::direction_angles(self.w_i[i]);
        let (tr, pr) = angles::direction_angles(self.w_r[i]);
        one_geometry(k, index, i, Geometry::new_unchecked(ti, pi, tr, pr))
    }
}

impl F32Blocks for Directions<'_> {
    #[inline(always)]
    fn lane_input<const N: usize>(scratch: &GeomScratch<N, f32>, j: usize) -> [f64; 6] {
        std::array::from_fn(|c| scratch.dirs[c][j])
    }

    #[inline(always)]
    fn theta_n_f64<M: Math<F = f64>>(x: [f64; 6]) -> f64 {
        // θN = atan2(|s_xy|, s_z) of the half vector s = ŵ_i + ŵ_r of the f64 vectors.
        let unit = |v: [f64; 3]| {
            let inv = 1.0 / M::mla(v[0], v[0], M::mla(v[1], v[1], v[2] * v[2])).sqrt();
            [v[0] * inv, v[1] * inv, v[2] * inv]
        };
        let (a, b) = (unit([x[0], x[1], x[2]]), unit([x[3], x[4], x[5]]));
        let s = [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
        M::atan2_pos(M::mla(s[0], s[0], s[1] * s[1]).sqrt(), s[2].max(0.0))
    }

    #[inline(always)]
    fn gathered_geometry<M: Math<F = f64>, const N: usize>(
        &self,
        pos: &[usize],
        needs: AngleNeeds,
        scratch: &mut GeomScratch<N>,
    ) {
        self.load::<N>(
            |j| pos[if j < pos.len() { j } else { 0 }],
            &mut scratch.dirs,
        );
        block::geometry_of_directions::<M, N, true>(scratch, needs);
    }
}

/// Explicit angle variables (the angle-variable entry point).
pub(super) struct Variables<'v>(pub(super) &'v [AngleVariables]);

impl Blocks for Variables<'_> {
    #[inline(always)]
    fn geometry<'s, M: Math, const N: usize, const PAIRS: bool>(
        &'s self,
        start: usize,
        len: usize,
        _needs: AngleNeeds,
        scratch: &'s mut GeomScratch<N, M::F>,
    ) -> &'s Geom<N, M::F>
    where
        M::F: Thresholds,
    {
        let v: [AngleVariables; N] =
            std::array::from_fn(|j| self.0[start + if j < len { j } else { 0 }]);
        block::geometry_of_variables(&v, &mut scratch.geo);
        &scratch.geo
    }

    fn reference(&self, k: &Kernel<'_>, index: IndexSource<'_>, i: usize) -> Evaluation {
        index
            .get(i, k.material)
            .map_or_else(Evaluation::undefined, |n| {
                k.material.evaluate_angles_with_index(&self.0[i], n)
            })
    }
}

/// The geometry stages of a batch, computed once ([`Kernel::prepare`]): what does not depend
/// on the material, per element, in the blocks the kernel evaluates.
#[derive(Clone)]
pub struct Prepared {
    level: SimdLevel,
    len: usize,
    blocks: Vec<Geom<BLOCK>>,
}

impl std::fmt::Debug for Prepared {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Prepared")
            .field("level", &self.level)
            .field("len", &self.len)
            .finish_non_exhaustive()
    }
}

impl Prepared {
    pub(super) fn with_capacity(n: usize, level: SimdLevel) -> Self {
        Self {
            level,
            len: 0,
            blocks: Vec::with_capacity(n.div_ceil(BLOCK)),
        }
    }

    /// Number of elements.
    pub fn len(&self) -> usize {
        self.len
    }

    /// True when there are none.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The SIMD level the geometry was computed with (kernels of this level use it).
    pub fn level(&self) -> SimdLevel {
        self.level
    }

    /// `other`'s elements after this one's (this one a whole number of blocks long).
    pub(crate) fn append(&mut self, other: Prepared) {
        assert_eq!(self.level, other.level, "prepared at one SIMD level");
        assert_eq!(self.len % BLOCK, 0, "appended after whole blocks");
        self.blocks.extend(other.blocks);
        self.len += other.len;
    }

    /// An empty batch prepared at `level`.
    pub(crate) fn empty(level: SimdLevel) -> Self {
        Self::with_capacity(0, level)
    }

    pub(super) fn push(&mut self, g: Geom<BLOCK>, len: usize) {
        self.blocks.push(g);
        self.len += len;
    }

    pub(super) fn range(&self, start: usize, len: usize, level: SimdLevel) -> PreparedRange<'_> {
        assert_eq!(
            self.level, level,
            "a batch prepared at one SIMD level evaluated at another"
        );
        assert!(
            start.is_multiple_of(BLOCK) && start + len <= self.len,
            "range {start}..{start}+{len} of a prepared batch of {} (start a multiple of {BLOCK})",
            self.len
        );
        PreparedRange {
            p: self,
            first: start / BLOCK,
        }
    }
}

/// The blocks of a prepared batch from block `first` on.
pub(super) struct PreparedRange<'p> {
    p: &'p Prepared,
    first: usize,
}

impl Blocks for PreparedRange<'_> {
    #[inline(always)]
    fn geometry<'s, M: Math, const N: usize, const PAIRS: bool>(
        &'s self,
        start: usize,
        _len: usize,
        _needs: AngleNeeds,
        _scratch: &'s mut GeomScratch<N, M::F>,
    ) -> &'s Geom<N, M::F>
    where
        M::F: Thresholds,
    {
        // Only whole blocks are prepared: the jobs run prepared batches with N = BLOCK. (A
        // partial last block was padded when prepared, as `load` pads.)
        assert!(start.is_multiple_of(BLOCK), "prepared blocks of {BLOCK}");
        let g: &dyn std::any::Any = &self.p.blocks[self.first + start / BLOCK];
        g.downcast_ref::<Geom<N, M::F>>()
            .expect("prepared blocks are evaluated in blocks of BLOCK")
    }

    fn reference(&self, k: &Kernel<'_>, index: IndexSource<'_>, i: usize) -> Evaluation {
        let g = &self.p.blocks[self.first + i / BLOCK];
        let a = |c: usize| g.angles[c][i % BLOCK];
        one_geometry(k, index, i, Geometry::new_unchecked(a(0), a(1), a(2), a(3)))
    }
}

/// Positions `pos` of a source, as a source.
pub(super) struct Gathered<'a, S> {
    src: &'a S,
    pos: &'a [usize],
}

impl<S: Source> Source for Gathered<'_, S> {
    #[inline(always)]
    fn get(&self, i: usize) -> [f64; 4] {
        self.src.get(self.pos[i])
    }
}
