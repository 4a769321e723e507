// Bird's-eye view figures: a 500-road OpenDRIVE network parsed and sampled (server side), then drawn by the
// view's own page in headless Chromium (the static layer), and a run played back (time to draw each frame).
// Run by bench/run.mjs with `node --import tsx`; prints figures, does not pass or fail.
import * as fs from 'node:fs';
import * as path from 'node:path';
import { birdsEyeHtml } from '../client/src/birdsEye/page';
import type { RenderStats, RunTracks } from '../client/src/birdsEye/messages';
import { parseOpenDrive } from '../server/src/core/opendrive/road';
import { sampleNetwork } from '../server/src/core/opendrive/sample';
import type { SceneResult } from '../common/src/sceneProtocol';

const root = path.resolve(__dirname, '..');
const chromium = process.env.M2S_CHROMIUM ?? '/usr/bin/chromium';
const town05 = path.resolve(root, '..', 'shared', 'esmini', 'xodr', 'Town05.xodr');

/** 500 roads on a grid, each a line, a spiral, an arc, a spiral back and a paramPoly3, with two lane sections and a lane offset. */
function syntheticNetwork(roads: number): string {
  const parts = ['<?xml version="1.0"?>\n<OpenDRIVE><header revMajor="1" revMinor="6"/>'];
  for (let i = 0; i < roads; i++) {
    const x0 = (i % 25) * 160;
    const y0 = Math.floor(i / 25) * 60;
    const lanes = (side: string, ids: number[]) =>
      `<${side}>${ids.map((id) => `<lane id="${id}" type="${Math.abs(id) === 3 ? 'sidewalk' : 'driving'}"><width sOffset="0" a="3.5" b="0" c="0.0005" d="-0.000002"/><width sOffset="40" a="3.6" b="0" c="0" d="0"/></lane>`).join('')}</${side}>`;
    const section = (s: number) =>
      `<laneSection s="${s}">${lanes('left', [3, 2, 1])}<center><lane id="0" type="none"/></center>${lanes('right', [-1, -2, -3])}</laneSection>`;
    parts.push(`<road id="${i}" length="140" junction="-1"><planView>
<geometry s="0" x="${x0}" y="${y0}" hdg="0" length="30"><line/></geometry>
<geometry s="30" x="${x0 + 30}" y="${y0}" hdg="0" length="20"><spiral curvStart="0" curvEnd="0.01"/></geometry>
<geometry s="50" x="${x0 + 50}" y="${y0 + 0.07}" hdg="0.1" length="30"><arc curvature="0.01"/></geometry>
<geometry s="80" x="${x0 + 79.7}" y="${y0 + 4.5}" hdg="0.4" length="20"><spiral curvStart="0.01" curvEnd="0"/></geometry>
<geometry s="100" x="${x0 + 98}" y="${y0 + 12}" hdg="0.5" length="40"><paramPoly3 aU="0" bU="1" cU="0" dU="0" aV="0" bV="0" cV="-0.01" dV="0" pRange="arcLength"/></geometry>
</planView><lanes><laneOffset s="0" a="0" b="0.01" c="0" d="0"/>${section(0)}${section(70)}</lanes></road>`);
  }
  parts.push('</OpenDRIVE>\n');
  return parts.join('\n');
}

function median(values: number[]): number {
  const sorted = [...values].sort((a, b) => a - b);
  return sorted[Math.floor(sorted.length / 2)];
}

function sceneOf(text: string, title: string): { scene: SceneResult; parseMs: number[]; sampleMs: number[] } {
  const parseMs: number[] = [];
  const sampleMs: number[] = [];
  let sections: SceneResult['sections'] = [];
  for (let i = 0; i < 7; i++) {
    const started = performance.now();
    const network = parseOpenDrive(text);
    const parsed = performance.now();
    sections = sampleNetwork(network);
    parseMs.push(parsed - started);
    sampleMs.push(performance.now() - parsed);
  }
  return { scene: { uri: `file:///${title}`, title, sections, entities: [], events: [], problems: [] }, parseMs, sampleMs };
}

/** Ten vehicles driving circles for 60 s at 0.05 s steps: the playback load. */
function syntheticRun(center: [number, number]): RunTracks {
  const times = Array.from({ length: 1201 }, (_, i) => i * 0.05);
  return {
    label: 'synthetic',
    times,
    entities: Array.from({ length: 10 }, (_, k) => ({
      name: `car${k}`,
      length: 4.5,
      width: 1.8,
      centerX: 1.4,
      x: times.map((t) => center[0] + (50 + 20 * k) * Math.cos(t / 5 + k)),
      y: times.map((t) => center[1] + (50 + 20 * k) * Math.sin(t / 5 + k)),
      hdg: times.map((t) => t / 5 + k + Math.PI / 2),
    })),
    starts: {},
    notes: [],
  };
}

async function main(): Promise<void> {
  const networks: { name: string; text: string }[] = [
    { name: '500 synthetic roads (line, spirals, arc, paramPoly3; 6 lanes, 2 sections)', text: syntheticNetwork(500) },
  ];
  if (fs.existsSync(town05)) networks.push({ name: 'CARLA Town05 (259 roads)', text: fs.readFileSync(town05, 'utf8') });
  else console.log(`(Town05 skipped: ${town05} is absent)`);

  const script = path.join(root, 'dist', 'birdsEye.js');
  const canDraw = fs.existsSync(chromium) && fs.existsSync(script);
  if (!canDraw) console.log(`(drawing skipped: needs ${chromium} and ${script})`);
  const { chromium: launcher } = await import('playwright-core');
  const browser = canDraw ? await launcher.launch({ executablePath: chromium, headless: true, args: ['--no-sandbox'] }) : undefined;

  console.log(
    `bird's-eye view benchmark (server: parse, sample, median of 7; view: headless Chromium, 1200 x 800 canvas; load average ${(await import('node:os')).loadavg()[0].toFixed(1)} on ${(await import('node:os')).cpus().length} cores)`,
  );
  for (const network of networks) {
    const { scene, parseMs, sampleMs } = sceneOf(network.text, network.name);
    const points = scene.sections.reduce(
      (sum, section) => sum + section.borders.reduce((count, border) => count + border.length / 2, 0),
      0,
    );
    const kb = JSON.stringify(scene).length / 1024;
    console.log(`  ${network.name}`);
    console.log(
      `    parse ${(network.text.length / 1024 / 1024).toFixed(1)} MB of XML: ${median(parseMs).toFixed(1)} ms; sample lane borders: ${median(sampleMs).toFixed(1)} ms median (${scene.sections.length} sections, ${points} points, ${kb.toFixed(0)} KB as JSON)`,
    );
    if (!browser) continue;
    const page = await (await browser.newContext({ bypassCSP: true, viewport: { width: 1200, height: 900 } })).newPage();
    await page.setContent(birdsEyeHtml('', 'about:blank', 'bench').replace(/<script[^]*?<\/script>/, ''));
    await page.evaluate(
      `window.__messages = []; window.acquireVsCodeApi = () => ({ postMessage: (message) => window.__messages.push(message) });`,
    );
    await page.addScriptTag({ path: script });
    const nextStats = async (after: number): Promise<RenderStats> => {
      await page.waitForFunction(`window.__messages.filter((m) => m.type === 'rendered').length > ${after}`);
      return (await page.evaluate(`window.__messages.filter((m) => m.type === 'rendered').at(-1).stats`)) as RenderStats;
    };
    const rendered = async () => (await page.evaluate(`window.__messages.filter((m) => m.type === 'rendered').length`)) as number;
    const draws: number[] = [];
    for (let i = 0; i < 5; i++) {
      const before = await rendered();
      await page.evaluate(`window.postMessage(${JSON.stringify({ type: 'scene', scene: { ...scene, uri: `${scene.uri}#${i}` } })}, '*')`);
      draws.push((await nextStats(before)).staticDrawMs);
    }
    // The transfer of the scene into the page and its first drawing, as a person waits for it.
    const before = await rendered();
    const started = Date.now();
    await page.evaluate(`window.postMessage(${JSON.stringify({ type: 'scene', scene: { ...scene, uri: `${scene.uri}#last` } })}, '*')`);
    await nextStats(before);
    const endToEnd = Date.now() - started;
    console.log(`    draw the roads (static layer): ${median(draws).toFixed(1)} ms median of 5; message to picture ${endToEnd} ms`);
    const bounds = scene.sections[0]?.borders[0] ?? [0, 0];
    const beforeRun = await rendered();
    await page.evaluate(`window.postMessage(${JSON.stringify({ type: 'run', run: syntheticRun([bounds[0], bounds[1]]) })}, '*')`);
    await nextStats(beforeRun);
    await page.click('#play');
    await page.waitForTimeout(3000);
    const beforePause = await rendered();
    await page.click('#play');
    const playing = await nextStats(beforePause);
    console.log(
      `    playing 10 vehicles with trajectories: ${playing.frames} frames in 3 s, draw ${playing.frameMeanMs.toFixed(2)} ms mean, ${playing.frameWorstMs.toFixed(2)} ms worst per frame (60 fps budget: 16.7 ms)`,
    );
    // Following one car, its speed, gap and TTC plotted under the map: the layer moves with it and is redrawn when it runs out.
    const beforeChoose = await rendered();
    await page.evaluate(`window.postMessage(${JSON.stringify({ type: 'choose', entity: 'car9' })}, '*')`);
    await nextStats(beforeChoose);
    await page.click('#play');
    await page.waitForTimeout(3000);
    const beforeFollowPause = await rendered();
    await page.click('#play');
    const following = await nextStats(beforeFollowPause);
    console.log(
      `    following car9 (46 m/s) with its plots: ${following.frames} frames in 3 s, draw ${following.frameMeanMs.toFixed(2)} ms mean, ${following.frameWorstMs.toFixed(2)} ms worst per frame`,
    );
    await page.close();
  }
  await browser?.close();
}

main().catch((error: unknown) => {
  console.error(error);
  process.exitCode = 1;
});
