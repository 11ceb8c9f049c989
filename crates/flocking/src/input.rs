//! Reading what a user gives: scenario and sweep files, bounded before they are read.
//!
//! A file is read only when it is a regular file (not a directory, a FIFO or a device such as
//! `/dev/zero`, which never ends) of at most [`MAX_INPUT_BYTES`]; a UTF-8 byte order mark at its
//! start is dropped. RON is parsed with a nesting limit of [`MAX_NESTING`] levels, far below what
//! would overflow a stack and far above what a scenario needs (about 6).

use std::io::Read;
use std::path::Path;

use ron::extensions::Extensions;

/// The largest scenario or sweep file read: 64 MiB (an explicit cloud of 10⁶ agents is ≈ 50 MB).
pub const MAX_INPUT_BYTES: u64 = 64 << 20;

/// The deepest nesting of RON values (and of values given to `with_values`) accepted.
pub const MAX_NESTING: usize = 64;

/// The text of the file at `path`, refused before reading when it is not a regular file or is
/// larger than [`MAX_INPUT_BYTES`]; a leading byte order mark removed.
///
/// # Errors
/// The reason, as a sentence naming the limit or the kind of file.
pub fn read_text(path: &Path) -> Result<String, String> {
    let metadata = std::fs::metadata(path).map_err(|e| {
        if e.kind() == std::io::ErrorKind::NotFound {
            // issue 27: the bare "No such file or directory (os error 2)" said nothing to do
            format!("{e}; check the path (relative paths start from the working directory)")
        } else {
            e.to_string()
        }
    })?;
    if !metadata.is_file() {
        let kind = if metadata.is_dir() {
            "a directory"
        } else {
            "not a regular file (a device, FIFO or socket)"
        };
        return Err(format!("it is {kind}; give the path of a .ron file"));
    }
    let too_large = |size: u64| {
        format!(
            "it holds {size} bytes, more than the limit of {MAX_INPUT_BYTES} bytes (64 MiB); \
             give a smaller file (an explicit cloud of 10^6 agents is about 50 MB)"
        )
    };
    if metadata.len() > MAX_INPUT_BYTES {
        return Err(too_large(metadata.len()));
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|file| file.take(MAX_INPUT_BYTES + 1).read_to_end(&mut bytes))
        .map_err(|e| e.to_string())?;
    if bytes.len() as u64 > MAX_INPUT_BYTES {
        return Err(too_large(bytes.len() as u64));
    }
    let text = String::from_utf8(bytes).map_err(|e| format!("it is not UTF-8 text: {e}"))?;
    Ok(without_bom(&text).to_owned())
}

/// `text` without a leading UTF-8 byte order mark.
#[must_use]
pub fn without_bom(text: &str) -> &str {
    text.strip_prefix('\u{feff}').unwrap_or(text)
}

/// The RON options of scenario and sweep files: `IMPLICIT_SOME`, nesting at most [`MAX_NESTING`].
#[must_use]
pub fn ron_options() -> ron::Options {
    ron::Options::default()
        .with_default_extension(Extensions::IMPLICIT_SOME)
        .with_recursion_limit(MAX_NESTING)
}

/// A RON error's message, with the nesting limit said in our terms.
#[must_use]
pub fn ron_message(error: &ron::Error) -> String {
    match error {
        ron::Error::ExceededRecursionLimit => format!(
            "values nested more than {MAX_NESTING} levels deep (a scenario needs about 6); \
             remove the extra brackets"
        ),
        other => other.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn refuses_what_is_not_a_regular_file() {
        let error = read_text(Path::new("/dev/zero")).unwrap_err();
        assert!(error.contains("not a regular file"), "{error}");
        let error = read_text(Path::new(env!("CARGO_MANIFEST_DIR"))).unwrap_err();
        assert!(error.contains("a directory"), "{error}");
    }

    #[test]
    fn refuses_a_file_over_the_limit_before_reading_it() {
        let path = std::env::temp_dir().join(format!("flock-large-{}.ron", std::process::id()));
        let file = std::fs::File::create(&path).unwrap();
        file.set_len(MAX_INPUT_BYTES + 1).unwrap(); // sparse: nothing written
        let error = read_text(&path).unwrap_err();
        std::fs::remove_file(&path).unwrap();
        assert!(error.contains("64 MiB"), "{error}");
    }

    #[test]
    fn drops_a_byte_order_mark() {
        assert_eq!(without_bom("\u{feff}Scenario("), "Scenario(");
        assert_eq!(without_bom("Scenario("), "Scenario(");
    }
}
