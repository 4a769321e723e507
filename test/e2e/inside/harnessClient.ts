import * as http from 'node:http';
import { HARNESS_ENV } from '../titles';

/** Talks to the harness endpoint (test/e2e/harness.ts) from inside the extension host. */
export function post<T>(route: string, body: unknown): Promise<T> {
  const endpoint = process.env[HARNESS_ENV.endpoint];
  if (!endpoint) return Promise.reject(new Error(`${HARNESS_ENV.endpoint} is not set; run these tests through test/e2e`));
  return new Promise((resolve, reject) => {
    const request = http.request(`${endpoint}${route}`, { method: 'POST', headers: { 'content-type': 'application/json' } }, (response) => {
      const chunks: Buffer[] = [];
      response.on('data', (chunk: Buffer) => chunks.push(chunk));
      response.on('end', () => {
        const text = Buffer.concat(chunks).toString('utf8');
        if (response.statusCode !== 200) reject(new Error(`${route}: ${text}`));
        else resolve(JSON.parse(text || '{}') as T);
      });
    });
    request.on('error', reject);
    request.end(JSON.stringify(body));
  });
}

/** A screenshot of the whole page as a person sees it now, kept under test-results/e2e/. */
export async function screenshot(name: string): Promise<void> {
  await new Promise((resolve) => setTimeout(resolve, 400));
  await post('/screenshot', { name });
}

/** Runs a command the way a person does: F1, its title, Enter. */
export async function runFromPalette(title: string): Promise<void> {
  await post('/palette', { title });
}

/** Presses keys in the page (e.g. 'F12'), as a person does. */
export async function pressKeys(keys: string[]): Promise<void> {
  await post('/keys', { keys });
}

/** Types text in the page, key by key, as a person does. */
export async function typeText(text: string): Promise<void> {
  await post('/type', { text });
}

/** Whether the page (any frame, or the elements matching `selector`) shows this text now. */
export async function pageShows(text: string, selector?: string): Promise<boolean> {
  return (await post<{ found: boolean }>('/findText', { text, selector })).found;
}

/** A computed style property of the first element matching each selector, in whichever frame has one (null: none). */
export async function computedStyles(selectors: string[], property: string): Promise<(string | null)[]> {
  return (await post<{ values: (string | null)[] }>('/computedStyles', { selectors, property })).values;
}

/** Where an element is drawn: CSS px in its frame, with its text as shown. */
export interface PageBox {
  left: number;
  top: number;
  right: number;
  bottom: number;
  text: string;
}

/** Every element matching `selector` in the first frame that has one (a webview's page too), where it is drawn now. */
export async function pageBoxes(selector: string): Promise<PageBox[]> {
  return (await post<{ boxes: PageBox[] }>('/boxes', { selector })).boxes;
}

/** Clicks the link or button showing this text, in whichever frame shows it. */
export async function clickText(text: string): Promise<boolean> {
  return (await post<{ clicked: boolean }>('/clickText', { text })).clicked;
}

/** Clicks the first element matching `selector` that shows `text`, in whichever frame has one (a webview's page too). */
export async function clickElement(selector: string, text: string): Promise<boolean> {
  return (await post<{ clicked: boolean }>('/clickElement', { selector, text })).clicked;
}

export interface QuickInputState {
  visible: boolean;
  value: string;
  title: string;
}

/** What the quick input shows now (the save dialog of a remote window is one). */
export async function quickInput(): Promise<QuickInputState> {
  return post<QuickInputState>('/quickInput', {});
}

/** Drags the first element matching `from` (a selector and a text it shows) onto the first matching `to`, with the mouse. */
export async function dragOnto(from: { selector: string; text: string }, to: { selector: string; text: string }): Promise<void> {
  await post('/drag', { from, to });
}
