//! Reading a probe ([`super::workloads::probes`]): what a sample timed with the calibration
//! but not fitted says one term costs where the calibration did not measure it.
//!
//! A probe does much of one term, and a little of others the families price well (an
//! off-screen strip's vertices, a draw, the submission). Its measured time less the fitted
//! prediction of everything but the term, per unit of the term, is the term's price the probe
//! implies; against the fitted price, the ratio says whether the fit's price holds there
//! (about 1) or what a frame doing that work pays beyond the model (above 1).

use super::{Sample, Term, UnitCosts};

/// What one probe sample says about the price of its term.
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct ProbeReading {
    /// The probe (`vertex_float_texture_loads`, ...).
    pub workload: String,
    /// The term it probes.
    pub term: Term,
    /// Units of the term it did (as counted, where the adapter counts).
    pub amount: f64,
    /// Its measured time (median of the rounds), ms.
    pub measured_ms: f64,
    /// The fitted costs' prediction of the whole sample, ms.
    pub predicted_ms: f64,
    /// The term's price the sample implies, in the unit costs' stored unit (ns for a texel
    /// load): `(measured − predicted without the term) / amount`.
    pub implied: f64,
    /// The fitted price, in the same unit.
    pub fitted: f64,
}

impl ProbeReading {
    /// Reads `sample`, a probe of `term`, under `costs`; `None` when the sample did none of
    /// the term or its time is not a positive number.
    pub fn read(costs: &UnitCosts, sample: &Sample, term: Term) -> Option<Self> {
        let amount = sample.work.amount(term);
        let timed = sample.measured_ms.is_finite() && sample.measured_ms > 0.0;
        if !(amount > 0.0 && timed) {
            return None;
        }
        let predicted_ms = costs.predict(&sample.work).total_ms;
        let per_unit_ms = costs.ms_per_unit(term);
        let others_ms = predicted_ms - amount * per_unit_ms;
        Some(Self {
            workload: sample.workload.clone(),
            term,
            amount,
            measured_ms: sample.measured_ms,
            predicted_ms,
            implied: (sample.measured_ms - others_ms) / amount / term.ms_per_stored_unit(),
            fitted: costs.get(term).value,
        })
    }

    /// Implied over fitted price (infinite where the fitted price is 0).
    pub fn ratio(&self) -> f64 {
        self.implied / self.fitted
    }

    /// Measured over predicted time of the whole sample.
    pub fn time_ratio(&self) -> f64 {
        self.measured_ms / self.predicted_ms
    }
}

/// The readings of probe samples as a Markdown table, one row a sample.
pub fn probes_markdown(readings: &[ProbeReading]) -> String {
    let mut md = String::from(
        "| probe | term | amount | measured ms | predicted ms | measured / predicted | implied price | fitted price | implied / fitted |\n|---|---|---:|---:|---:|---:|---:|---:|---:|\n",
    );
    for r in readings {
        md.push_str(&format!(
            "| {} | {} | {:.0} | {:.2} | {:.2} | {:.2} | {:.3} | {:.3} | {:.2} |\n",
            r.workload,
            r.term,
            r.amount,
            r.measured_ms,
            r.predicted_ms,
            r.time_ratio(),
            r.implied,
            r.fitted,
            r.ratio()
        ));
    }
    md
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cost::{UnitCost, Work};

    #[test]
    fn the_implied_price_is_what_the_time_leaves_for_the_term() {
        // In ms per unit: a 0.5 ms submission, 20 ns a vertex, 0.6 ns a float texel load.
        let mut per_unit = [UnitCost::exact(0.0); Term::ALL.len()];
        per_unit[Term::Fixed.index()] = UnitCost::exact(0.5);
        per_unit[Term::Vertex.index()] = UnitCost::exact(20e-6);
        per_unit[Term::FloatTextureLoad.index()] = UnitCost::exact(0.6e-6);
        let costs = UnitCosts::from_ms_per_unit(
            "640x360".into(),
            "test".into(),
            per_unit,
            Default::default(),
        );
        // 100 000 vertices (2 ms) loading 3.2 M float texels (1.92 ms at the fitted price),
        // a 0.5 ms submission: predicted 4.42 ms. Measured 10.82 ms leaves 8.32 ms for the
        // loads: 2.6 ns each, 4.33x the fitted 0.6.
        let sample = Sample {
            workload: "vertex_float_texture_loads".into(),
            measured_ms: 10.82,
            work: Work {
                vertex_invocations: 1e5,
                float_texture_loads: 3.2e6,
                ..Work::default()
            },
        };
        let r = ProbeReading::read(&costs, &sample, Term::FloatTextureLoad).unwrap();
        assert!((r.predicted_ms - 4.42).abs() < 1e-9, "{r:?}");
        assert!((r.implied - 2.6).abs() < 1e-9, "{r:?}");
        assert!((r.ratio() - 2.6 / 0.6).abs() < 1e-9);
        assert!((r.time_ratio() - 10.82 / 4.42).abs() < 1e-9);
        // A sample the costs explain implies the fitted price.
        let exact = Sample {
            measured_ms: 4.42,
            ..sample.clone()
        };
        let r = ProbeReading::read(&costs, &exact, Term::FloatTextureLoad).unwrap();
        assert!((r.ratio() - 1.0).abs() < 1e-9, "{r:?}");
        assert!(probes_markdown(&[r]).contains("| vertex_float_texture_loads | float_texture_load | 3200000 | 4.42 | 4.42 | 1.00 | 0.600 | 0.600 | 1.00 |"));
        // Nothing of the term, or no time: nothing to read.
        assert!(ProbeReading::read(&costs, &sample, Term::TextureLoad).is_none());
        let untimed = Sample {
            measured_ms: f64::NAN,
            ..sample
        };
        assert!(ProbeReading::read(&costs, &untimed, Term::FloatTextureLoad).is_none());
    }
}
