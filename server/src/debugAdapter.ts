// The debug adapter's process entry (dist/debugAdapter.js): the Debug Adapter Protocol over stdin and stdout. As the
// editor starts it, it supervises (debug/supervisor.ts); its child, started with SESSION_ARGUMENT, is the session.
// The session is a bundle of its own (dist/debugSession.js), required only in the child: the supervisor starts without
// reading or running it, and the child is started that much sooner (docs/benchmarks.md, F5's first launch).
import { existsSync } from 'node:fs';
import { join } from 'node:path';
import { CODE_CACHE_ENV, loadWithCodeCache } from './debug/codeCache';
import { SESSION_ARGUMENT, superviseSession } from './debug/supervisor';

type SessionBundle = typeof import('./debugSession');

/** The session's bundle, from V8's code cache in the folder the editor names when it names one (debug/codeCache.ts). */
function sessionBundle(): SessionBundle {
  const cacheFolder = process.env[CODE_CACHE_ENV];
  // From the sources (the tests, through tsx) there is no bundle beside this file: the session is a module as any.
  const bundle = 'debugSession.js';
  if (cacheFolder && __filename.endsWith('.js') && existsSync(join(__dirname, bundle)))
    return loadWithCodeCache<SessionBundle>(__dirname, bundle, require, cacheFolder).exports;
  return require('./debugSession') as SessionBundle;
}

if (process.argv.includes(SESSION_ARGUMENT)) sessionBundle().runSession();
else superviseSession(process.argv[1]);
