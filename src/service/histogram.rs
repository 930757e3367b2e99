//! Latency percentiles without allocating per sample: a fixed histogram of 10 µs
//! buckets up to 100 ms, the exact maximum kept beside it.

use std::time::Duration;

/// Bucket width, microseconds.
const BUCKET_US: u64 = 10;
/// Buckets: 0 to 100 ms; anything slower lands in the last one (the maximum is exact).
const BUCKETS: usize = 10_000;

/// A latency histogram: allocated once, then [`Histogram::record`] only counts.
#[derive(Debug, Clone)]
pub struct Histogram {
    counts: Box<[u32]>,
    count: u64,
    max_us: u64,
}

/// Median, 99th percentile and maximum of a [`Histogram`], microseconds (percentiles
/// to the bucket's upper edge, 10 µs).
#[derive(Debug, Clone, Copy, Default, PartialEq, serde::Serialize)]
pub struct Percentiles {
    /// Samples.
    pub count: u64,
    /// Median, µs.
    pub p50_us: u64,
    /// 99th percentile, µs.
    pub p99_us: u64,
    /// Maximum, µs.
    pub max_us: u64,
}

impl Default for Histogram {
    fn default() -> Self {
        Self::new()
    }
}

impl Histogram {
    /// An empty histogram.
    pub fn new() -> Self {
        Histogram {
            counts: vec![0; BUCKETS].into_boxed_slice(),
            count: 0,
            max_us: 0,
        }
    }

    /// Count one sample.
    pub fn record(&mut self, d: Duration) {
        let us = u64::try_from(d.as_micros()).unwrap_or(u64::MAX);
        let b = ((us / BUCKET_US) as usize).min(BUCKETS - 1);
        self.counts[b] = self.counts[b].saturating_add(1);
        self.count += 1;
        self.max_us = self.max_us.max(us);
    }

    /// Samples counted.
    pub fn count(&self) -> u64 {
        self.count
    }

    /// Forget every sample (keeps the buckets' memory).
    pub fn clear(&mut self) {
        self.counts.fill(0);
        self.count = 0;
        self.max_us = 0;
    }

    /// The value below which a fraction `q` of the samples lie, µs (bucket upper edge,
    /// never above the maximum).
    fn quantile_us(&self, q: f64) -> u64 {
        if self.count == 0 {
            return 0;
        }
        let rank = ((q * self.count as f64).ceil() as u64).clamp(1, self.count);
        let mut seen = 0u64;
        for (i, &c) in self.counts.iter().enumerate() {
            seen += u64::from(c);
            if seen >= rank {
                return ((i as u64 + 1) * BUCKET_US).min(self.max_us);
            }
        }
        self.max_us
    }

    /// Median, p99 and maximum.
    pub fn percentiles(&self) -> Percentiles {
        Percentiles {
            count: self.count,
            p50_us: self.quantile_us(0.5),
            p99_us: self.quantile_us(0.99),
            max_us: self.max_us,
        }
    }
}

impl std::fmt::Display for Percentiles {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "p50 {:.2} p99 {:.2} max {:.2} ms",
            self.p50_us as f64 / 1e3,
            self.p99_us as f64 / 1e3,
            self.max_us as f64 / 1e3
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentiles_of_a_known_spread() {
        let mut h = Histogram::new();
        assert_eq!(h.percentiles(), Percentiles::default());
        // 1..=100 ms... in µs: 1000, 2000, ..., 100_000 (the last past the buckets).
        for k in 1..=100u64 {
            h.record(Duration::from_micros(k * 1000));
        }
        let p = h.percentiles();
        assert_eq!(p.count, 100);
        assert_eq!(
            p.p50_us, 50_010,
            "the bucket holding 50 ms ends at 50.01 ms"
        );
        assert_eq!(p.max_us, 100_000);
        assert_eq!(p.p99_us, 99_010);
        h.clear();
        assert_eq!(h.count(), 0);
        h.record(Duration::from_micros(3));
        assert_eq!(h.percentiles().p50_us, 3, "never above the maximum");
    }
}
