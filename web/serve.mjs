// A static HTTP server for the player and the browser tests: the project's web/ and tests/web/
// (the pages, web/build, web/node_modules) at /web/ and /tests/web/, and a folder of files at
// /files/. It answers HTTP range requests, as a web server hosting .mvid files would.
// Loopback only. It counts the bytes of /files/ it sends (server.bytesServed) and can send
// them at a set rate, as a slow network would (the streaming test).
import { once } from 'node:events';
import { createReadStream, existsSync, statSync } from 'node:fs';
import http from 'node:http';
import path from 'node:path';
import { setTimeout as sleep } from 'node:timers/promises';

const TYPES = { '.mjs': 'text/javascript', '.js': 'text/javascript', '.html': 'text/html',
                '.css': 'text/css', '.wasm': 'application/wasm', '.png': 'image/png',
                '.json': 'application/json' };

/** Starts serving `root` at / and `files` at /files/ on 127.0.0.1:`port` (0: any free one),
 * the files at `bytesPerSecond` if given; resolves to the http.Server. */
export async function serve(root, files, port = 0, { bytesPerSecond = 0 } = {}) {
  root = path.resolve(root);
  files = path.resolve(files);
  const server = http.createServer((request, response) => {
    const relative = decodeURIComponent(new URL(request.url, 'http://localhost').pathname);
    // The pages and what they load (web/, tests/web/), and the files; nothing else of the tree.
    const [base, file] = relative.startsWith('/files/')
      ? [files, path.join(files, relative.slice('/files/'.length))]
      : /^\/(web|tests\/web)\//.test(relative) ? [root, path.join(root, relative)] : [root, ''];
    if (!file.startsWith(base + path.sep) || !existsSync(file) || !statSync(file).isFile()) {
      response.writeHead(404).end();
      return;
    }
    const size = statSync(file).size;
    const isFile = base === files;
    const headers = { 'content-type': TYPES[path.extname(file)] ?? 'application/octet-stream',
                      'accept-ranges': 'bytes', 'cache-control': 'no-store' };
    const range = /^bytes=(\d*)-(\d*)$/.exec(request.headers.range ?? '');
    if (range && (range[1] || range[2])) {
      const start = range[1] ? Number(range[1]) : Math.max(0, size - Number(range[2]));
      const end = range[1] && range[2] ? Math.min(Number(range[2]), size - 1) : size - 1;
      if (start > end || start >= size) {
        response.writeHead(416, { 'content-range': `bytes */${size}` }).end();
        return;
      }
      response.writeHead(206, { ...headers, 'content-range': `bytes ${start}-${end}/${size}`,
                                'content-length': end - start + 1 });
      send(createReadStream(file, { start, end }), response, isFile);
      return;
    }
    response.writeHead(200, { ...headers, 'content-length': size });
    send(createReadStream(file), response, isFile);
  });
  server.bytesServed = 0;
  /** Sends `stream`; a file's bytes are counted, and paced when a rate is set. */
  const send = (stream, response, isFile) => {
    if (!isFile || !bytesPerSecond) {
      if (isFile) stream.on('data', (chunk) => { server.bytesServed += chunk.length; });
      stream.pipe(response);
      return;
    }
    (async () => {
      for await (const chunk of stream) {
        await sleep(1000 * chunk.length / bytesPerSecond);
        if (response.destroyed) break;  // the client went away
        server.bytesServed += chunk.length;
        if (!response.write(chunk)) {
          await Promise.race([once(response, 'drain'), once(response, 'close')]);
        }
      }
      response.end();
    })().catch(() => response.destroy()).finally(() => stream.destroy());
  };
  await new Promise((resolve, reject) => {
    server.once('error', reject);
    server.listen(port, '127.0.0.1', resolve);
  });
  return server;
}
