// What the playground refuses, with a message, to stay responsive. Real templates are a
// few dozen characters and real prints a few thousand layers; the CLI has no such caps.
export const MAX_TEMPLATE = 64 * 1024; // characters in the editor
export const MAX_LAYERS = 2_000_000; // layers evaluated and plotted
export const WORKER_TIMEOUT_MS = 10_000; // then the worker is stopped and restarted
export const MAX_MESH = 64 * 1024 * 1024; // bytes of a mesh file (1.3 million STL triangles)
