//! wasm-bindgen glue: starting the app on a canvas, and the automation API that `www/main.js`
//! puts on `window.proctex` (documented in `www/README.md`).

use wasm_bindgen::prelude::*;

use crate::app::{Command, ProctexApp, SNAPSHOT, send};
use proctex::params::Params;

/// The running app (so JS can ask whether it panicked).
#[wasm_bindgen]
pub struct WebHandle {
    runner: eframe::WebRunner,
}

impl std::fmt::Debug for WebHandle {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("WebHandle").finish_non_exhaustive()
    }
}

#[wasm_bindgen]
impl WebHandle {
    /// Whether the app panicked (the page then shows the message).
    pub fn has_panicked(&self) -> bool {
        self.runner.has_panicked()
    }

    /// The panic message, if it panicked.
    pub fn panic_message(&self) -> Option<String> {
        self.runner.panic_summary().map(|s| s.message())
    }
}

/// Starts the app on `canvas`. Fails (with a message) when the browser has no WebGPU.
#[wasm_bindgen]
pub async fn start(canvas: web_sys::HtmlCanvasElement) -> Result<WebHandle, JsValue> {
    let runner = eframe::WebRunner::new();
    let options = eframe::WebOptions::default();
    runner
        .start(
            canvas,
            options,
            Box::new(|cc| Ok(Box::new(ProctexApp::new(cc)))),
        )
        .await?;
    Ok(WebHandle { runner })
}

/// Analyses a decoded image (interleaved 8-bit RGBA, `width × height`) and shows the texture.
#[wasm_bindgen(js_name = loadPixels)]
pub fn load_pixels(rgba: Vec<u8>, width: u32, height: u32, name: String) {
    send(Command::LoadPixels {
        rgba,
        width,
        height,
        name,
    });
}

/// Shows an error message in the app (e.g. a file the browser could not decode).
#[wasm_bindgen(js_name = reportError)]
pub fn report_error(message: String) {
    send(Command::Error(message));
}

/// The current params as JSON (`proctex/1`), or `null` before the first analysis.
#[wasm_bindgen(js_name = getParams)]
pub fn get_params() -> Option<String> {
    SNAPSHOT.with(|s| s.borrow().params_json.clone())
}

/// Replaces the params; throws the validation message when the document is bad.
#[wasm_bindgen(js_name = setParams)]
pub fn set_params(json: String) -> Result<(), JsValue> {
    let p = Params::from_json(&json).map_err(|e| JsValue::from_str(&e.to_string()))?;
    send(Command::SetParams(Box::new(p)));
    Ok(())
}

/// Sets the texture view: world point at the view's top-left, world units per CSS pixel.
#[wasm_bindgen(js_name = setView)]
pub fn set_view(origin_x: f32, origin_y: f32, units_per_point: f32) {
    send(Command::SetView {
        origin: [origin_x, origin_y],
        units_per_point,
    });
}

/// Asks for another frame (egui repaints only on events; tests use this to step frames).
#[wasm_bindgen(js_name = requestRepaint)]
pub fn request_repaint() {
    crate::app::CONTEXT.with(|c| {
        if let Some(ctx) = c.borrow().as_ref() {
            ctx.request_repaint();
        }
    });
}

/// The app's state after the last frame, as JSON: frame, photo, analysis_ms, error, widgets
/// (name → [x, y, w, h] in CSS pixels), view, undo/redo depths.
#[wasm_bindgen]
pub fn state() -> String {
    SNAPSHOT.with(|s| serde_json::to_string(&*s.borrow()).unwrap_or_default())
}
