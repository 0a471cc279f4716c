//! The MSL's random number generators (`Modelica.Math.Random`, external C functions of
//! `ModelicaRandom.c`) and its string hash (`ModelicaStrings_hashString`), written in
//! Rust: xorshift64*, xorshift128+ and xorshift1024* on state vectors of 32-bit Integers (two per
//! 64-bit word, the low half first), and the AP hash of a string.

/// `2^-64`.
const INV_2_64: f64 = 5.421_010_862_427_522e-20;

/// A 64-bit word from two Integer state entries (the low half first).
fn word(lo: f64, hi: f64) -> u64 {
    let half = |v: f64| u64::from(v as i64 as i32 as u32);
    half(lo) | (half(hi) << 32)
}

/// The two Integer state entries of a 64-bit word (the low half first).
fn halves(x: u64) -> [f64; 2] {
    [
        f64::from(x as u32 as i32),
        f64::from((x >> 32) as u32 as i32),
    ]
}

/// A number in (0, 1) from a 64-bit word: the word as a signed integer times 2^-64,
/// plus 1/2 (zero cannot appear).
fn uniform(x: u64) -> f64 {
    (x as i64) as f64 * INV_2_64 + 0.5
}

/// One step of xorshift64*: the random number and the new state (2 entries).
pub fn xorshift64star(state: [f64; 2]) -> (f64, [f64; 2]) {
    let mut x = word(state[0], state[1]);
    x ^= x >> 12;
    x ^= x << 25;
    x ^= x >> 27;
    x = x.wrapping_mul(2_685_821_657_736_338_717);
    (uniform(x), halves(x))
}

/// One step of xorshift128+: the random number and the new state (4 entries).
pub fn xorshift128plus(state: [f64; 4]) -> (f64, [f64; 4]) {
    let mut s1 = word(state[0], state[1]);
    let s0 = word(state[2], state[3]);
    s1 ^= s1 << 23;
    let next = (s1 ^ s0 ^ (s1 >> 17) ^ (s0 >> 26)).wrapping_add(s0);
    let [a, b] = halves(s0);
    let [c, d] = halves(next);
    (uniform(next), [a, b, c, d])
}

/// One step of xorshift1024* (`ModelicaRandom_xorshift1024star_internal`) from the
/// two words it reads, `s[p]` and `s[p + 1]`: the word it writes at `s[p + 1]` (the
/// new position `p`) and the random number.
pub fn xorshift1024star_word(s0: u64, s1: u64) -> (u64, f64) {
    let mut s1 = s1;
    let mut s0 = s0;
    s1 ^= s1 << 31;
    s1 ^= s1 >> 11;
    s0 ^= s0 >> 30;
    let next = s0 ^ s1;
    (next, uniform(next.wrapping_mul(1_181_783_497_276_652_981)))
}

/// Output `k` of one xorshift1024* step on the words `s[p]` and `s[p + 1]` given as
/// Integer halves `[s0 lo, s0 hi, s1 lo, s1 hi]`: 0 the random number, 1 and 2 the
/// halves of the new word.
pub fn xorshift1024star(ops: [f64; 4], k: u8) -> f64 {
    let (next, r) = xorshift1024star_word(word(ops[0], ops[1]), word(ops[2], ops[3]));
    match k {
        0 => r,
        1 => halves(next)[0],
        _ => halves(next)[1],
    }
}

/// The MSL's hash of a string (the AP hash over its bytes, as a signed 32-bit Integer).
pub fn hash_string(text: &str) -> i32 {
    let mut h: u32 = 0xAAAA_AAAA;
    for (i, &byte) in text.as_bytes().iter().enumerate() {
        let c = u32::from(byte);
        h ^= if i & 1 == 0 {
            (h << 7) ^ c.wrapping_mul(h >> 3)
        } else {
            !((h << 11).wrapping_add(c ^ (h >> 5)))
        };
    }
    h as i32
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hash_matches_the_msl_documentation() {
        // The examples of Modelica.Utilities.Strings.hashString's documentation.
        assert_eq!(hash_string("this is a test"), 1_827_717_433);
        assert_eq!(hash_string("Controller.noise1"), -1_025_762_750);
    }

    #[test]
    fn generators_step_their_state() {
        // xorshift128+ moves the second word into the first.
        let (r, s) = xorshift128plus([1.0, 2.0, 3.0, 4.0]);
        assert_eq!([s[0], s[1]], [3.0, 4.0]);
        assert!(r > 0.0 && r < 1.0);
        // xorshift64* of the state 1: x = 1 ^ (1 << 25) then times the multiplier.
        let (r, s) = xorshift64star([1.0, 0.0]);
        let x = (1u64 ^ (1 << 25)).wrapping_mul(2_685_821_657_736_338_717);
        assert_eq!(word(s[0], s[1]), x);
        assert_eq!(r, (x as i64) as f64 * INV_2_64 + 0.5);
        // Negative Integers are their two's-complement halves.
        assert_eq!(word(-1.0, 0.0), 0xFFFF_FFFF);
        assert_eq!(halves(0xFFFF_FFFF_0000_0001), [1.0, -1.0]);
    }
}
