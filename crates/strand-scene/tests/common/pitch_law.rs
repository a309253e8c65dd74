//! The section law followed along a curvature path at stations over one pitch, each with its
//! committed slip state, and the wires' friction moments it splits into per layer: the
//! `stick_scaling` test and the `layer_moments` example both read the law this way.

use strand_core::{SectionLaw, Station, Strand};

/// The law's stations at the middles of `n` equal parts of the first layer's pitch.
pub fn pitch_stations(law: &SectionLaw, strand: &Strand, n: usize) -> Vec<Station> {
    let pitch = strand.layers()[0].pitch;
    (0..n)
        .map(|i| law.station(pitch * (i as f64 + 0.5) / n as f64))
        .collect()
}

/// The law at the stations of one pitch with the slip state it commits at each.
pub struct PitchLaw {
    pub law: SectionLaw,
    pub stations: Vec<Station>,
    slip: Vec<Vec<f64>>,
    trial: Vec<f64>,
    /// Per layer: the wires' projected axial stiffness k = eta E_w A_w (N) and lay radius (m).
    k_radius: Vec<(f64, f64)>,
}

impl PitchLaw {
    /// `law` at `n` stations over the first layer's pitch of `strand`, unslipped.
    pub fn new(law: SectionLaw, strand: &Strand, n: usize) -> Self {
        let stations = pitch_stations(&law, strand, n);
        // K_stick of a layer is n k R^2 / 2 over the station's n wires of the layer.
        let k_radius = strand
            .layers()
            .iter()
            .enumerate()
            .map(|(j, h)| {
                let n = stations[0].wires.iter().filter(|w| w.layer == j).count() as f64;
                (
                    2.0 * law.layer_stick_stiffness(j) / (n * h.radius * h.radius),
                    h.radius,
                )
            })
            .collect();
        let len = law.state_len();
        Self {
            law,
            stations,
            slip: vec![vec![0.0; len]; n],
            trial: vec![0.0; len],
            k_radius,
        }
    }

    /// Number of helical layers.
    pub fn layers(&self) -> usize {
        self.k_radius.len()
    }

    /// Moves the law at every station to strain `eps` and curvature `kappa` (1/m) and commits
    /// its slip state. At each station, `wire(layer, m)` receives each wire's friction moment
    /// m = k (l kappa - s) l (N m), s its committed slip strain and l = -R sin(phi) its lever,
    /// and `station(law, station, committed slip, law's moment)` follows. That K_min kappa plus the
    /// station's friction moments is the law's moment M is checked: a panic where they differ
    /// by more than `rel` times the larger of |M| and `floor` (N m).
    pub fn step(
        &mut self,
        eps: f64,
        kappa: f64,
        (rel, floor): (f64, f64),
        mut wire: impl FnMut(usize, f64),
        mut station: impl FnMut(&SectionLaw, &Station, &[f64], f64),
    ) {
        for (st, slip) in self.stations.iter().zip(&mut self.slip) {
            let r = self.law.planar(st, eps, kappa, slip, &mut self.trial);
            slip.copy_from_slice(&self.trial);
            let mut parts = self.law.planar_linear(eps, kappa).moment;
            for (i, w) in st.wires.iter().enumerate() {
                let (k, radius) = self.k_radius[w.layer];
                let lever = -radius * w.phase.sin();
                let m = k * (lever * kappa - slip[i]) * lever;
                wire(w.layer, m);
                parts += m;
            }
            assert!(
                (parts - r.moment).abs() <= rel * r.moment.abs().max(floor),
                "per-wire forces {parts} against the law's moment {}",
                r.moment
            );
            station(&self.law, st, slip, r.moment);
        }
    }
}
