import { randomBytes } from 'node:crypto';

/** A nonce for a webview page's Content-Security-Policy: unguessable, so only the page's own scripts run. */
export function webviewNonce(): string {
  return randomBytes(18).toString('hex');
}
