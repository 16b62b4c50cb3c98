//! Decimal parameters of escape sequences: how many bytes a number takes, and writing it.

/// Bytes of `n` in decimal (escape parameters are never wider than five digits).
#[inline]
pub(crate) fn digits(n: u32) -> u32 {
    let mut d = 1;
    let mut n = n;
    while n >= 10 {
        n /= 10;
        d += 1;
    }
    d
}

/// Appends `n` in decimal without allocating.
#[inline]
pub(crate) fn push_num(out: &mut Vec<u8>, n: u32) {
    if n < 10 {
        out.push(b'0' + n as u8);
    } else if n < 100 {
        out.extend_from_slice(&[b'0' + (n / 10) as u8, b'0' + (n % 10) as u8]);
    } else if n < 1000 {
        out.extend_from_slice(&[
            b'0' + (n / 100) as u8,
            b'0' + (n / 10 % 10) as u8,
            b'0' + (n % 10) as u8,
        ]);
    } else {
        push_num(out, n / 10);
        out.push(b'0' + (n % 10) as u8);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn digits_match_the_written_form() {
        for n in [0, 9, 10, 99, 100, 255, 999, 1000, 65535, 123_456] {
            let mut v = Vec::new();
            push_num(&mut v, n);
            assert_eq!(v, n.to_string().into_bytes());
            assert_eq!(digits(n) as usize, v.len());
        }
    }
}
