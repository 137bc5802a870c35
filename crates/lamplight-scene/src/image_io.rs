//! Image writers: placeholder (replaced in this session).
