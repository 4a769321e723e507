// Loads tsx for mocha without its compile cache, which it would keep in os.tmpdir() after the run: a run
// leaves nothing in the temporary directory (test/support/temporaryDirectory.ts checks the rest).
process.env.TSX_DISABLE_CACHE = '1';
await import('tsx');
