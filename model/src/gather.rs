//! Registers copied into a state's array (the outputs and their analogs after the outputs'
//! segment): the registers' bound checked once per copy, not once per value.

/// The registers `regs[k]` whose values a copy writes to `dst[k]`.
#[derive(Clone, Debug, Default)]
pub(crate) struct Gather {
    regs: Vec<u32>,
    /// One more than the largest register: the registers a copy needs.
    needs: usize,
}

impl Gather {
    /// The copy of the registers `regs`, in order.
    pub(crate) fn new(regs: Vec<u32>) -> Gather {
        let needs = regs.iter().max().map_or(0, |&m| m as usize + 1);
        Gather { regs, needs }
    }

    /// `dst[k] = r[regs[k]]` for each `k` of both.
    #[inline(always)]
    pub(crate) fn run(&self, r: &[f64], dst: &mut [f64]) {
        assert!(r.len() >= self.needs, "registers of another model");
        for (d, &k) in dst.iter_mut().zip(&self.regs) {
            // SAFETY: every register is below `needs` <= `r.len()`.
            *d = unsafe { *r.get_unchecked(k as usize) };
        }
    }

    /// The sum of the registers' values.
    #[inline(always)]
    pub(crate) fn sum(&self, r: &[f64]) -> f64 {
        assert!(r.len() >= self.needs, "registers of another model");
        let mut s = 0.0;
        for &k in &self.regs {
            // SAFETY: every register is below `needs` <= `r.len()`.
            s += unsafe { *r.get_unchecked(k as usize) };
        }
        s
    }
}
