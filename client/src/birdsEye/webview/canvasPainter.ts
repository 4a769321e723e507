/** The Painter (../draw.ts) that draws on a canvas. */
import type { Painter } from '../draw';

export function canvasPainter(target: CanvasRenderingContext2D): Painter {
  const path = (xy: ArrayLike<number>) => {
    target.beginPath();
    target.moveTo(xy[0], xy[1]);
    for (let i = 2; i + 1 < xy.length; i += 2) target.lineTo(xy[i], xy[i + 1]);
  };
  return {
    polygon(xy, fill) {
      path(xy);
      target.closePath();
      target.fillStyle = fill;
      target.fill();
    },
    polyline(xy, stroke, width, dash) {
      path(xy);
      target.strokeStyle = stroke;
      target.lineWidth = width;
      target.setLineDash(dash ?? []);
      target.stroke();
    },
    clip(x, y, width, height) {
      target.save();
      target.beginPath();
      target.rect(x, y, width, height);
      target.clip();
    },
    unclip() {
      target.restore();
    },
    text(x, y, text, color, size) {
      target.font = `${size}px sans-serif`;
      target.lineWidth = 3;
      target.strokeStyle = 'rgba(0,0,0,0.7)';
      target.setLineDash([]);
      target.strokeText(text, x, y);
      target.fillStyle = color;
      target.fillText(text, x, y);
    },
  };
}
