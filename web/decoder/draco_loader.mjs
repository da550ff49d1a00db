// Loads a Draco decoder module from the URL of its classic script (three.js's
// draco_decoder.js), in a page or a module worker (which has no importScripts).

/** Resolves to the Draco decoder module the script at `url` defines (DracoDecoderModule). */
export async function loadDracoDecoder(url) {
  const response = await fetch(url);
  if (!response.ok) throw new Error(`${url}: HTTP ${response.status}`);
  const factory = new Function(`${await response.text()}\nreturn DracoDecoderModule;`)();
  // Wrapped: the module is a thenable, which `await` would unwrap forever.
  return new Promise((resolve) => {
    factory({ onModuleLoaded: (module) => resolve({ module }) });
  }).then(({ module }) => module);
}
