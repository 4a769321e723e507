import { ChildProcess, spawn, spawnSync } from 'node:child_process';
import * as fs from 'node:fs';
import * as net from 'node:net';
import { temporaryFolder } from './temporaryDirectory';
import { waitUntil } from './wait';

/** A free TCP port on 127.0.0.1 (nothing listens on it once this resolves). */
export async function freePort(): Promise<number> {
  return new Promise((resolve, reject) => {
    const server = net.createServer();
    server.on('error', reject);
    server.listen(0, '127.0.0.1', () => {
      const port = (server.address() as net.AddressInfo).port;
      server.close(() => resolve(port));
    });
  });
}

export interface RedisServer {
  url: string;
  port: number;
  stop(): Promise<void>;
}

/**
 * Skips the calling test when Debian's redis-server is not installed (scripts/test-all.sh installs it as root).
 * With M2S_REQUIRE_REDIS set (CI), a missing redis-server fails instead.
 */
export function requireRedis(context: Mocha.Context): void {
  if (spawnSync('redis-server', ['--version']).status === 0) return;
  const why = 'redis-server is not installed (apt-get install redis-server)';
  if (process.env.M2S_REQUIRE_REDIS) throw new Error(`M2S_REQUIRE_REDIS is set, but ${why}`);
  console.log(`    (skipped: ${why})`);
  context.skip();
}

/** A redis-server of the test's own on 127.0.0.1 and a free port, with no persistence, in a temporary folder. */
export async function startRedis(): Promise<RedisServer> {
  const port = await freePort();
  const dir = temporaryFolder('m2s-redis-');
  const child: ChildProcess = spawn(
    'redis-server',
    ['--port', String(port), '--bind', '127.0.0.1', '--save', '', '--appendonly', 'no', '--dir', dir],
    { stdio: 'ignore' },
  );
  let exited = false;
  child.on('exit', () => (exited = true));
  await waitUntil(
    () => {
      if (exited) throw new Error('redis-server exited at start');
      return spawnSync('redis-cli', ['-h', '127.0.0.1', '-p', String(port), 'ping'], { encoding: 'utf8' }).stdout.trim() === 'PONG';
    },
    'redis-server to answer',
    20_000,
    50,
  );
  return {
    url: `redis://127.0.0.1:${port}`,
    port,
    async stop() {
      if (!exited) {
        child.kill('SIGTERM');
        await waitUntil(() => exited, 'redis-server to stop', 10_000);
      }
      fs.rmSync(dir, { recursive: true, force: true });
    },
  };
}
