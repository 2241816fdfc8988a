// Reads the shared conformance corpus (../shared/conformance beside the checkout, or
// $ROTLANG_CONFORMANCE), as the Rust conformance test does.
import { readFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
export const conformanceDir = process.env.ROTLANG_CONFORMANCE
  ?? resolve(here, '../../../../shared/conformance');

export function jsonl(name) {
  return readFileSync(resolve(conformanceDir, name), 'utf8')
    .split('\n')
    .filter((l) => l.trim())
    .map((l) => JSON.parse(l));
}

export const models = JSON.parse(readFileSync(resolve(conformanceDir, 'models.json'), 'utf8'));

const TOLERANCE = 1e-4;

/** Same direction modulo 360 within 1e-4 degrees; relative 1e-9 above 1e9 (corpus README). */
export function sameDirection(got, expected) {
  if (Math.abs(expected) > 1e9) return Math.abs(got - expected) <= 1e-9 * Math.abs(expected);
  const diff = (((got - expected) % 360) + 360) % 360;
  return diff <= TOLERANCE || diff >= 360 - TOLERANCE;
}

/** Inside [min, max] modulo 360 within the tolerance. */
export function within(got, min, max) {
  const shifted = got - 360 * Math.floor((got - min + TOLERANCE) / 360);
  return shifted <= max + TOLERANCE || sameDirection(got, min) || sameDirection(got, max);
}
