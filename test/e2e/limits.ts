// The harness's time limits, in a module of their own: the setup files the inside suite bundles import them too.

/**
 * The longest the run may go without progress (a setup step done, a request from the tests inside VS Code),
 * rather than one limit for the whole run, which a busy machine overran: more than the longest an inside test
 * waits without a request (120 s, see test/e2e/inside/helpers.ts), so that a slow test fails there, by name,
 * before the harness gives up; and the limit of each setup step (packaging, a batch of esmini runs) at a load of 25.
 */
export const STALL_MS = 300_000;

/**
 * How long the page may take to do what a test asks of it (a click, the command palette opening): Playwright's
 * limit for one action, generous as the tests' own waits are (test/e2e/inside/helpers.ts WAIT_MS).
 */
export const PAGE_ACTION_MS = 60_000;
