//! Q16.16 fixed point in C: an `int32_t` whose value is `bits / 65536`, the bits of the
//! library's `I16F16`.

use stiffspring::I16F16;

/// One in Q16.16: `STIFFSPRING_Q16_ONE` (65536).
///
/// ```c
/// int32_t half = STIFFSPRING_Q16_ONE / 2; /* 0.5 */
/// ```
pub const STIFFSPRING_Q16_ONE: i32 = 1 << 16;

/// The `I16F16` of Q16.16 bits.
pub(crate) fn from_bits(bits: i32) -> I16F16 {
    I16F16::from_bits(bits)
}

/// The Q16.16 bits of an `I16F16`.
pub(crate) fn to_bits(value: I16F16) -> i32 {
    value.to_bits()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bits_round_trip() {
        assert_eq!(from_bits(STIFFSPRING_Q16_ONE), I16F16::ONE);
        assert_eq!(
            to_bits(I16F16::from_num(-1.5)),
            -3 * STIFFSPRING_Q16_ONE / 2
        );
        assert_eq!(to_bits(from_bits(i32::MIN)), i32::MIN);
    }
}
