/**
 * The page's lists, rebuilt when the scene or the runs change: entities, events and their timeline markers,
 * problems, the title, the follow list.
 */
import { setTime } from './controls';
import { compareMode, element, followList, playButton, slider } from './dom';
import { eventRows, eventRowText, groupText, type EventRow } from '../eventList';
import { open } from './host';
import { colorOf, duration, state } from './state';

function button(label: string, title: string, onClick: () => void, className = ''): HTMLButtonElement {
  const result = document.createElement('button');
  result.textContent = label;
  result.title = title;
  result.className = className;
  result.addEventListener('click', onClick);
  return result;
}

/** The event list as the panel shows it (and a saved picture copies). */
export function shownEventRows(): EventRow[] {
  const phase = state.running ? 'live' : state.run ? 'finished' : 'none';
  return eventRows(state.scene?.events ?? [], state.run, phase, state.running);
}

export function renderPanel(): void {
  const entities = element<HTMLDivElement>('entities');
  entities.replaceChildren();
  for (const entity of state.scene?.entities ?? []) {
    const item = button(
      `■ ${entity.name}`,
      `${entity.kind}: ${entity.described}${entity.problem ? ` — ${entity.problem}` : ''}`,
      () => open(entity.source),
      'entity',
    );
    item.style.color = colorOf(entity.name);
    entities.append(item);
  }
  const events = element<HTMLUListElement>('events');
  const markers = element<HTMLDivElement>('markers');
  events.replaceChildren();
  markers.replaceChildren();
  const total = duration();
  for (const row of shownEventRows()) {
    const item = document.createElement('li');
    const title = `${row.path ?? row.name}\n${row.trigger}`;
    item.append(
      button(row.name, title, () => open(row.source), 'event'),
      ` ${eventRowText(row).slice(row.name.length + 1)}`,
    );
    item.className = [row.running ? 'running' : '', row.state === 'never' ? 'never' : ''].filter(Boolean).join(' ');
    events.append(item);
    const at = row.start ?? row.plannedTime;
    if (at !== undefined && total > 0 && at <= total) {
      const marker = document.createElement('div');
      marker.className = row.start !== undefined ? 'marker started' : 'marker planned';
      marker.style.left = `${(at / total) * 100}%`;
      marker.title = `${row.name} (${row.actor}, ${groupText(row)}): ${row.when}`;
      marker.addEventListener('click', () => {
        setTime(at);
        open(row.source);
      });
      markers.append(marker);
    }
  }
  const cursor = document.createElement('div');
  cursor.id = 'cursor';
  markers.append(cursor);
  const problems = element<HTMLUListElement>('problems');
  const drawn = state.scene?.roadFile?.resolved;
  // The run and the picture resolve the road alike (core/semantics/roadFiles.ts); a run loaded elsewhere (an older CSV, another tool) is said so.
  const otherRoad =
    state.run?.roadFile && drawn && state.run.roadFile !== drawn
      ? [`the run loaded the road file ${state.run.roadFile}; the picture draws ${drawn}`]
      : [];
  problems.replaceChildren(
    ...[...(state.scene?.problems ?? []), ...(state.run?.notes ?? []), ...otherRoad].map((problem) =>
      Object.assign(document.createElement('li'), { textContent: problem }),
    ),
  );
  const road = state.scene?.roadFile
    ? ` · road ${drawn ?? `${state.scene.roadFile.filepath} (not found)`}${drawn ? ` (${state.scene.roadFile.roadCount} road${state.scene.roadFile.roadCount === 1 ? '' : 's'})` : ''}`
    : '';
  const title = element<HTMLSpanElement>('title');
  title.textContent = state.scene ? `${state.scene.title}${road}${state.run ? ` · run: ${state.run.label}` : ''}` : 'loading…';
  title.title = drawn ? `The road file drawn: ${drawn} (${state.scene?.roadFile?.filepath} as the scenario says)` : '';
  const names = [
    ...new Set([...(state.run?.entities.map((track) => track.name) ?? []), ...(state.scene?.entities.map((entity) => entity.name) ?? [])]),
  ];
  if (state.chosen && !names.includes(state.chosen)) state.chosen = undefined;
  followList.replaceChildren(
    Object.assign(document.createElement('option'), { value: '', textContent: 'Follow: none' }),
    ...names.map((name) => Object.assign(document.createElement('option'), { value: name, textContent: `Follow ${name}` })),
  );
  followList.value = state.following && state.chosen ? state.chosen : '';
  if (state.compare) title.textContent += ` · compared with: ${state.compare.label}${state.sideBySide ? ' (right)' : ' (dashed)'}`;
  compareMode.style.display = state.compare ? '' : 'none';
  compareMode.value = state.sideBySide ? 'side' : 'overlay';
  const hasRun = state.run !== undefined;
  playButton.disabled = !hasRun;
  slider.disabled = !hasRun;
}
