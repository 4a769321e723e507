/** The page's elements (written by ../page.ts) that the script reads and changes. */
export const element = <T extends HTMLElement>(id: string) => document.getElementById(id) as T;
export const canvas = element<HTMLCanvasElement>('canvas');
export const stage = element<HTMLDivElement>('stage');
export const tooltip = element<HTMLDivElement>('tooltip');
export const slider = element<HTMLInputElement>('slider');
export const playButton = element<HTMLButtonElement>('play');
export const timeLabel = element<HTMLSpanElement>('time');
export const followList = element<HTMLSelectElement>('follow');
export const plotsCanvas = element<HTMLCanvasElement>('plots');
export const compareMode = element<HTMLSelectElement>('compareMode');
