//! Checks that every length a schema or channel record of an MCAP file states lies inside the
//! record, before the `mcap` crate parses it: its parser reserves a string's stated length (up to
//! 4 GiB from four damaged bytes) before reading it.

const U16: usize = 2;

/// Whether the body of a schema record (id, name, encoding, data) holds what it states.
pub fn schema_fits(body: &[u8]) -> bool {
    let mut fields = Fields { rest: body };
    fields.skip(U16) && fields.string() && fields.string() && fields.string()
}

/// Whether the body of a channel record (id, schema id, topic, message encoding, metadata)
/// holds what it states.
pub fn channel_fits(body: &[u8]) -> bool {
    let mut fields = Fields { rest: body };
    if !(fields.skip(2 * U16) && fields.string() && fields.string()) {
        return false;
    }
    let Some(map_len) = fields.length() else {
        return false;
    };
    let Some(map) = fields.rest.get(..map_len) else {
        return false;
    };
    let mut entries = Fields { rest: map };
    while !entries.rest.is_empty() {
        if !(entries.string() && entries.string()) {
            return false;
        }
    }
    true
}

/// What is left of a record's body as its fields are read.
struct Fields<'a> {
    rest: &'a [u8],
}

impl Fields<'_> {
    fn skip(&mut self, bytes: usize) -> bool {
        match self.rest.get(bytes..) {
            Some(rest) => {
                self.rest = rest;
                true
            }
            None => false,
        }
    }

    /// A little-endian `u32` length.
    fn length(&mut self) -> Option<usize> {
        let bytes: [u8; 4] = self.rest.get(..4)?.try_into().ok()?;
        self.rest = &self.rest[4..];
        usize::try_from(u32::from_le_bytes(bytes)).ok()
    }

    /// A length-prefixed string (or byte array), which must fit.
    fn string(&mut self) -> bool {
        self.length().is_some_and(|len| self.skip(len))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn string(text: &str) -> Vec<u8> {
        [&(text.len() as u32).to_le_bytes()[..], text.as_bytes()].concat()
    }

    #[test]
    fn a_whole_schema_and_channel_fit_and_an_overlong_string_does_not() {
        let schema = [
            &[1, 0][..],
            &string("a/msg/B"),
            &string("ros2msg"),
            &string("int32 x\n"),
        ]
        .concat();
        assert!(schema_fits(&schema));
        let mut long = schema.clone();
        long[2..6].copy_from_slice(&u32::MAX.to_le_bytes());
        assert!(!schema_fits(&long));
        assert!(!schema_fits(&schema[..schema.len() - 1]));

        let entry = [string("offered_qos_profiles"), string("")].concat();
        let metadata = [&(entry.len() as u32).to_le_bytes()[..], &entry].concat();
        let channel = [&[1, 0, 1, 0][..], &string("/t"), &string("cdr"), &metadata].concat();
        assert!(channel_fits(&channel));
        let mut long = channel.clone();
        let key_at = channel.len() - entry.len();
        long[key_at..key_at + 4].copy_from_slice(&1_000_000u32.to_le_bytes());
        assert!(!channel_fits(&long));
    }
}
