//! Lowering of `ModelicaFFT_kiss_fftr` (`rawRealFFT`): an FFT reads a whole vector,
//! while an expression node has at most four operands. The input is therefore written
//! to a run-time scratch area of the FFT's site by [`ExtFn::FftPush`] nodes (three
//! values each, at explicit positions), tied together by a balanced tree of
//! [`ExtFn::FftJoin`] nodes, and each output is an [`ExtFn::RealFft`] node of that tree
//! (so that every push is computed before it). The runtime (`unimo_runtime::fft`)
//! computes the transform ([`crate::fft::real_fft`]) once per distinct input.

use crate::error::DaeError;
use crate::expr::ExprId;
use crate::external::ExtFn;
use crate::lower::Lowerer;
use crate::tensor::Tensor;
use unimo_flat::functions::{ExternalCall, FlatFunction};
use unimo_source::Span;

impl Lowerer<'_> {
    /// `info = ModelicaFFT_kiss_fftr(u, size(u, 1), work, size(work, 1), amplitudes,
    /// phases)`: the outputs named by the call's last two arguments and its result.
    pub(crate) fn real_fft(
        &mut self,
        f: &FlatFunction,
        ext: &ExternalCall,
        span: Span,
    ) -> Result<(), DaeError> {
        let u = self.foreign_arg(ext, 0, span)?.data;
        let n = u.len();
        let name = |k: usize| match ext.args.get(k).map(|a| &a.kind) {
            Some(unimo_syntax::ast::ExprKind::Ref(r)) if r.parts.len() == 1 => {
                Some(r.parts[0].name.text.to_string())
            }
            _ => None,
        };
        let (Some(amplitudes), Some(phases), Some(info)) = (name(4), name(5), ext.output.clone())
        else {
            return Err(DaeError::FftOutputs {
                function: f.name.to_string(),
                foreign: ext.function.to_string(),
                span,
            });
        };
        let site = self.fft_sites;
        self.fft_sites += 1;
        let end = self.fft_input(site, &u);
        let n_c = self.dae.arena.constant(n as f64);
        let nf = n / 2 + 1;
        let output = |me: &mut Self, kind: u8, k: usize| {
            let kc = me.dae.arena.constant(k as f64);
            me.ext_node(ExtFn::RealFft(kind), &[end, kc, n_c])
        };
        let amps: Vec<ExprId> = (0..nf).map(|k| output(self, 0, k)).collect();
        let phis: Vec<ExprId> = (0..nf).map(|k| output(self, 1, k)).collect();
        let info_value = output(self, 2, 0);
        self.assign_outputs([
            (amplitudes, Tensor::vector(amps)),
            (phases, Tensor::vector(phis)),
            (info, Tensor::scalar(info_value)),
        ]);
        Ok(())
    }

    /// The pushes of `u` to the scratch area of `site`, joined: the node every output
    /// reads.
    fn fft_input(&mut self, site: usize, u: &[ExprId]) -> ExprId {
        let base = site as f64 * crate::fft::SITE_STRIDE;
        let zero = self.dae.arena.zero();
        let mut level: Vec<ExprId> = u
            .chunks(3)
            .enumerate()
            .map(|(c, vals)| {
                let slot = self.dae.arena.constant(base + (3 * c) as f64);
                let get = |k: usize| vals.get(k).copied().unwrap_or(zero);
                self.ext_node(ExtFn::FftPush, &[slot, get(0), get(1), get(2)])
            })
            .collect();
        if level.is_empty() {
            let slot = self.dae.arena.constant(base);
            level.push(self.ext_node(ExtFn::FftPush, &[slot, zero, zero, zero]));
        }
        while level.len() > 1 {
            level = level
                .chunks(2)
                .map(|pair| match pair {
                    [a, b] => self.ext_node(ExtFn::FftJoin, &[*a, *b]),
                    _ => pair[0],
                })
                .collect();
        }
        level[0]
    }
}
