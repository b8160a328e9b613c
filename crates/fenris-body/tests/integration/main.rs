//! Integration tests of fenris-body: one module per file.

mod block_on_line;
