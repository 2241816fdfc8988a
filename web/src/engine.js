// The main thread's side of the worker: requests as promises, and a watchdog that stops
// and restarts the worker when a request takes too long.
import { WORKER_TIMEOUT_MS } from './limits.js';

export class Engine {
  constructor(onRestart = () => {}) {
    this.onRestart = onRestart;
    this.next = 1;
    this.spawn();
  }

  spawn() {
    this.worker = new Worker(new URL('./worker.js', import.meta.url), { type: 'module' });
    this.pending = new Map();
    this.worker.onmessage = ({ data }) => {
      const p = this.pending.get(data.id);
      if (!p) return;
      this.pending.delete(data.id);
      clearTimeout(p.timer);
      if (data.ok) p.resolve(data.result);
      else p.reject(Object.assign(new Error(data.error.message), data.error));
    };
    this.worker.onerror = (e) => this.fail({ kind: 'internal', message: `the worker failed: ${e.message ?? 'unknown error'}` });
  }

  // Rejects everything in flight and starts a fresh worker.
  fail(error) {
    this.worker.terminate();
    const pending = [...this.pending.values()];
    this.spawn();
    for (const p of pending) {
      clearTimeout(p.timer);
      p.reject(Object.assign(new Error(error.message), error));
    }
    this.onRestart(error);
  }

  request(op, args, timeout = WORKER_TIMEOUT_MS) {
    const id = this.next++;
    return new Promise((resolve, reject) => {
      const timer = setTimeout(() => this.fail({
        kind: 'timeout',
        message: `stopped: rotlang took more than ${timeout / 1000} s (${op})`,
      }), timeout);
      this.pending.set(id, { resolve, reject, timer });
      this.worker.postMessage({ id, op, args });
    });
  }
}
