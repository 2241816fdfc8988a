// Examples from the language documentation (the "Quick examples" and "Complex template
// examples" sections), with the documentation's own words.
export const EXAMPLES = [
  ['0, 90', 'alternate 0° and 90° each layer'],
  ['0, 15, 30', 'alternate 0°, 15° and 30° each layer'],
  ['+90', 'rotate 90° each layer'],
  ['+45', 'rotate 45° each layer for higher dispersion'],
  ['+30/50%', 'linearly rotate by 30° over the next 50% of model height'],
  ['+45/10#', 'linearly rotate by 45° across 10 standard layers'],
  ['+15#10', 'keep the angle for 10 layers, then rotate +15°'],
  ['B!, +30', 'skip the bottom shell layers, then rotate 30° per layer'],
  ['0, +30, +90', 'a repeating sequence of 0°, +30°, +90°'],
  ['5, 10!, +20', 'a one-time instruction in a sequence'],
  ['-50%Z1cm', 'a sine turn of -50% over 1 cm'],
  ['+10L25%, -10l25%, -10L25%, +10l25%', 'a sine period with 10° amplitude over the model'],
  ['+30/-10#', 'rotate inverse linearly by 30° over 10 standard layers'],
  ['+360~100%', 'a random direction on each layer'],
  ['#14, +15R', 'every 14th layer rectilinear solid, turning 15°'],
  ['B!, 240M3, #25', 'bottom shells kept, monotonic solid layers, a 25-layer step'],
  ['+30/1cm, ST', 'a linear turn over 1 cm, then the top shells solid'],
];
