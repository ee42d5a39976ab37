// The analysis worker's image helpers: decoding a photo file, its RGBA pixels, and the preview
// sent to the UI.
export const PREVIEW_SIDE = 1024; // longest side of the preview sent to the UI (crop panel, split view)

export async function decode(bytes) {
  return createImageBitmap(new Blob([bytes]), { imageOrientation: 'from-image' });
}

export function pixelsOf(bitmap) {
  const { width, height } = bitmap;
  const ctx = new OffscreenCanvas(width, height).getContext('2d', { willReadFrequently: true });
  ctx.drawImage(bitmap, 0, 0);
  return new Uint8Array(ctx.getImageData(0, 0, width, height).data.buffer);
}

export function previewOf(bitmap) {
  const k = Math.min(1, PREVIEW_SIDE / Math.max(bitmap.width, bitmap.height));
  const w = Math.max(1, Math.round(bitmap.width * k));
  const h = Math.max(1, Math.round(bitmap.height * k));
  const ctx = new OffscreenCanvas(w, h).getContext('2d', { willReadFrequently: true });
  ctx.imageSmoothingQuality = 'high';
  ctx.drawImage(bitmap, 0, 0, w, h);
  return { preview: new Uint8Array(ctx.getImageData(0, 0, w, h).data.buffer), pw: w, ph: h };
}
