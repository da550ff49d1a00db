// A static HTTP server for the player and the browser tests: the project's web/ and tests/web/
// (the pages, web/build, web/node_modules) at /web/ and /tests/web/, and a folder of files at
// /files/. It answers HTTP range requests, as a web server hosting .mvid files would.
// Loopback only.
import { createReadStream, existsSync, statSync } from 'node:fs';
import http from 'node:http';
import path from 'node:path';

const TYPES = { '.mjs': 'text/javascript', '.js': 'text/javascript', '.html': 'text/html',
                '.css': 'text/css', '.wasm': 'application/wasm', '.png': 'image/png',
                '.json': 'application/json' };

/** Starts serving `root` at / and `files` at /files/ on 127.0.0.1:`port` (0: any free one);
 * resolves to the http.Server. */
export async function serve(root, files, port = 0) {
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
      createReadStream(file, { start, end }).pipe(response);
      return;
    }
    response.writeHead(200, { ...headers, 'content-length': size });
    createReadStream(file).pipe(response);
  });
  await new Promise((resolve, reject) => {
    server.once('error', reject);
    server.listen(port, '127.0.0.1', resolve);
  });
  return server;
}
