//! Progress of the passes a basis file read in blocks ([`crate::BasisFileBlocks`]) makes over
//! its stored columns: a [`BlockObserver`] is called on the calling thread at the start of each
//! pass and after every block of it, with a [`BlockProgress`] — enough for a progress bar, and
//! a place where a caller can stop the pass (a callback that unwinds: Python's Ctrl+C).

use std::sync::Arc;

/// What a pass over a basis file does with the blocks it reads.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum BlockPass {
    /// The check when the file is opened: the payload read through once for its checksum and
    /// for every stored value being finite.
    Checking,
    /// A projection `Uᵀ M1 v` (the Fourier coefficients of a field).
    Projecting,
    /// A synthesis `U c` of one or more coefficient sets.
    Synthesising,
    /// Every basis field formed once (the basis id compressed files carry).
    Fields,
    /// The rows of `U` a spline's or soft design's constraints touch.
    Rows,
}

impl BlockPass {
    /// Its name in reports: `checking`, `projecting`, `synthesising`, `fields`, `rows`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Checking => "checking",
            Self::Projecting => "projecting",
            Self::Synthesising => "synthesising",
            Self::Fields => "fields",
            Self::Rows => "rows",
        }
    }
}

/// How far a pass over a basis file has come, in bytes of the file: `done_bytes` of
/// `total_bytes` (`0` at the start of the pass, `total_bytes` after its last block). The
/// checking pass counts the payload it reads (eigenvalues, families and stored columns); the
/// others count the stored columns they cover — read whole, or for [`BlockPass::Rows`] read
/// only at the entries the rows touch (a few reads per column, counted as the column's bytes).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BlockProgress {
    /// The pass.
    pub pass: BlockPass,
    /// Bytes of the pass done, `0 ≤ done_bytes ≤ total_bytes`.
    pub done_bytes: u64,
    /// Bytes the pass covers in all (more than `0`: empty passes are not reported).
    pub total_bytes: u64,
}

/// A callback for the progress of every pass over a basis file read in blocks, called between
/// blocks on the thread that called the product (never from inside the blocks' parallel work;
/// a product called from worker threads, several at once, reports from each): it may unwind to
/// stop the pass (the file and the blocks are left as they were).
pub type BlockObserver = Arc<dyn Fn(BlockProgress) + Send + Sync>;

/// One pass in progress: reports its start on creation and each block on [`Self::advance`].
pub(crate) struct PassProgress<'a> {
    observer: Option<&'a BlockObserver>,
    pass: BlockPass,
    done_bytes: u64,
    total_bytes: u64,
}

impl<'a> PassProgress<'a> {
    /// A pass `pass` of `total_bytes`, reported to `observer` (if any; nothing for an empty
    /// pass) as started.
    pub(crate) fn start(
        observer: Option<&'a BlockObserver>,
        pass: BlockPass,
        total_bytes: u64,
    ) -> Self {
        let progress = Self {
            observer: observer.filter(|_| total_bytes > 0),
            pass,
            done_bytes: 0,
            total_bytes,
        };
        progress.report();
        progress
    }

    /// `bytes` more of the pass done (a block read and used), reported.
    pub(crate) fn advance(&mut self, bytes: u64) {
        self.done_bytes = (self.done_bytes + bytes).min(self.total_bytes);
        self.report();
    }

    fn report(&self) {
        if let Some(observer) = self.observer {
            observer(BlockProgress {
                pass: self.pass,
                done_bytes: self.done_bytes,
                total_bytes: self.total_bytes,
            });
        }
    }
}
