//! Seeded randomness for the `~` and `^` joints: a pure function of (seed, layer index),
//! so a layer's angle does not depend on the order in which layers are evaluated.

/// SplitMix64's finaliser: a bijection on u64 with good avalanche.
#[inline]
fn mix(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// A number in `[0, 1)` for layer `index` under `seed`.
#[inline]
pub(crate) fn unit(seed: u64, index: usize) -> f64 {
    // Mixing the index before the seed keeps (seed, index) and (seed + 1, index - 1) apart.
    let bits = mix(seed ^ mix((index as u64).wrapping_add(0x9e37_79b9_7f4a_7c15)));
    // The top 53 bits fill an f64 mantissa exactly.
    (bits >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

#[cfg(test)]
mod tests {
    use super::unit;

    #[test]
    fn in_range_and_pure() {
        for seed in [0, 1, u64::MAX] {
            for index in 0..1000 {
                let r = unit(seed, index);
                assert!((0.0..1.0).contains(&r));
                assert_eq!(r.to_bits(), unit(seed, index).to_bits());
            }
        }
    }

    #[test]
    fn seeds_and_indices_differ() {
        assert_ne!(unit(0, 0), unit(1, 0));
        assert_ne!(unit(0, 0), unit(0, 1));
        let mean = (0..10_000).map(|i| unit(7, i)).sum::<f64>() / 10_000.0;
        assert!((mean - 0.5).abs() < 0.02, "mean {mean}");
    }
}
