//! Tests of the EuRoC layout on small datasets the tests make: write → read round trip, the
//! written files checked against the published format by an independent parser, a hand-written
//! published-style sequence read, and bad inputs.

mod bad_input;
mod fixture;
mod published_format;
mod round_trip;
