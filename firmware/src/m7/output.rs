//! The firmware's output over semihosting (the protocol is in the module above): lines, the
//! hex-streamed postcard encoding of a result, and the exit on failure.

use core::fmt::Write as _;

use cortex_m_semihosting::hio;

use super::measure::systick;
use super::runtime::fail;
use super::Fixture;

/// Semihosting output; a failure to print is fatal (the tests read this output).
pub struct Out(hio::HostStream);

impl Out {
    pub fn new() -> Self {
        match hio::hstdout() {
            Ok(stream) => Self(stream),
            Err(()) => fail(),
        }
    }

    fn bytes(&mut self, bytes: &[u8]) {
        if self.0.write_all(bytes).is_err() {
            fail();
        }
    }
}

impl core::fmt::Write for Out {
    fn write_str(&mut self, s: &str) -> core::fmt::Result {
        self.bytes(s.as_bytes());
        Ok(())
    }
}

/// A postcard flavor that streams the encoding as lowercase hex, so no buffer the size of a
/// `Solution` is needed.
struct HexFlavor<'a> {
    out: &'a mut Out,
    buf: [u8; 256],
    len: usize,
}

impl<'a> HexFlavor<'a> {
    fn new(out: &'a mut Out) -> Self {
        Self {
            out,
            buf: [0; 256],
            len: 0,
        }
    }

    fn flush(&mut self) {
        let len = self.len;
        self.out.bytes(&self.buf[..len]);
        self.len = 0;
    }
}

impl postcard::ser_flavors::Flavor for HexFlavor<'_> {
    type Output = ();

    fn try_push(&mut self, byte: u8) -> postcard::Result<()> {
        const DIGITS: &[u8; 16] = b"0123456789abcdef";
        if self.len + 2 > self.buf.len() {
            self.flush();
        }
        self.buf[self.len] = DIGITS[usize::from(byte >> 4)];
        self.buf[self.len + 1] = DIGITS[usize::from(byte & 0xf)];
        self.len += 2;
        Ok(())
    }

    fn finalize(mut self) -> postcard::Result<()> {
        self.flush();
        Ok(())
    }
}

/// Print a `result` line: the postcard encoding of `result`, streamed as hex. Never inlined:
/// its buffer is not part of the caller's frame, so the stack high-water of an answer is the
/// answer's alone.
#[inline(never)]
pub fn print_result<T: serde::Serialize>(out: &mut Out, index: usize, result: &T) {
    let _ = write!(out, "result index={index} hex=");
    if postcard::serialize_with_flavor(result, HexFlavor::new(out)).is_err() {
        let _ = writeln!(
            Out::new(),
            "\nerror: cannot encode the result of fixture {index}"
        );
        fail();
    }
    out.bytes(b"\n");
}

/// A fixture's figures line: name, planner, outcome, stack high-water, SysTick instructions
/// and (when the planner has a work meter) work units. Never inlined, as [`print_result`].
#[inline(never)]
pub fn report(
    out: &mut Out,
    index: usize,
    fixture: &Fixture,
    planner: &str,
    ok: bool,
    stack_bytes: usize,
    (ticks, work_units): (u64, Option<u64>),
) {
    let _ = write!(
        out,
        "fixture index={index} name={} planner={planner} outcome={} stack_bytes={stack_bytes} \
         systick_instructions={}",
        fixture.name,
        if ok { "ok" } else { "error" },
        ticks * systick::INSTRUCTIONS_PER_TICK,
    );
    match work_units {
        Some(units) => {
            let _ = writeln!(out, " work_units={units}");
        }
        None => {
            let _ = writeln!(out);
        }
    }
}
