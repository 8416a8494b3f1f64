//! Write faults for the end-to-end tests of all-or-nothing outputs and of interruption: the
//! environment variable [`WRITE_FAULT_VARIABLE`] set to `fail:NAME` makes the write of every
//! file called `NAME` (the last path component) fail as on a full disk once its content is
//! written, `stall:NAME` makes it wait a minute there, as on a very slow disk (to interrupt the
//! process then). The libraries never read the environment: the variable is read here and
//! handed to them as a hook ([`tvf_core::io::inject_write_faults`]).

use std::path::Path;
use std::sync::OnceLock;
use tvf_core::io::WriteFault;

/// The variable the tests set.
pub const WRITE_FAULT_VARIABLE: &str = "TVF_TEST_WRITE_FAULT";

/// Installs the hook if the variable is set; call once at the start.
pub fn install() {
    if fault_request().is_some() {
        tvf_core::io::inject_write_faults(injected_fault);
    }
}

/// The fault and the file name of [`WRITE_FAULT_VARIABLE`], read once.
fn fault_request() -> Option<&'static (WriteFault, String)> {
    static REQUEST: OnceLock<Option<(WriteFault, String)>> = OnceLock::new();
    REQUEST
        .get_or_init(|| {
            let value = std::env::var(WRITE_FAULT_VARIABLE).ok()?;
            parse(&value)
        })
        .as_ref()
}

/// `fail:NAME` or `stall:NAME`.
fn parse(value: &str) -> Option<(WriteFault, String)> {
    let (fault, name) = value.split_once(':')?;
    let fault = match fault {
        "fail" => WriteFault::Fail,
        "stall" => WriteFault::Stall,
        _ => return None,
    };
    Some((fault, name.to_string()))
}

/// The hook: the requested fault for a file of the requested name.
fn injected_fault(path: &Path) -> Option<WriteFault> {
    let (fault, name) = fault_request()?;
    (path.file_name()? == name.as_str()).then_some(*fault)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn requests_are_parsed() {
        assert_eq!(
            parse("fail:x.npy"),
            Some((WriteFault::Fail, "x.npy".into()))
        );
        assert_eq!(parse("stall:a:b"), Some((WriteFault::Stall, "a:b".into())));
        assert_eq!(parse("explode:x"), None);
        assert_eq!(parse("fail"), None);
    }
}
