import * as fs from 'node:fs';
import * as path from 'node:path';
import { temporaryFolder } from './temporaryDirectory';

/**
 * A fresh temporary folder (its real path) holding the given files (paths relative to it); `prefix` starts its
 * name. It is removed when the top-level `describe` that made it ends (test/support/temporaryDirectory.ts).
 */
export function temporaryWorkspace(files: Record<string, string | Uint8Array> = {}, prefix = 'm2s-test-'): string {
  const root = temporaryFolder(prefix);
  for (const [name, content] of Object.entries(files)) {
    const full = path.join(root, name);
    fs.mkdirSync(path.dirname(full), { recursive: true });
    fs.writeFileSync(full, content);
  }
  return root;
}

/** Every file below a folder, relative paths, sorted: to assert that nothing was written. */
export function listFiles(root: string): string[] {
  const found: string[] = [];
  const walk = (directory: string) => {
    for (const entry of fs.readdirSync(directory, { withFileTypes: true })) {
      const full = path.join(directory, entry.name);
      if (entry.isDirectory()) walk(full);
      else found.push(path.relative(root, full));
    }
  };
  walk(root);
  return found.sort();
}
