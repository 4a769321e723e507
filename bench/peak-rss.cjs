// Preloaded into a measured process: reports its peak resident memory on exit, on file descriptor 2.
process.on('exit', () => {
  process.stderr.write(`\n@@peak-rss-kb ${process.resourceUsage().maxRSS}\n`);
});
