//! The HTTP and WebSocket server (axum): the page, the scene's own files and
//! one WebSocket per page.
//!
//! Every request must name this server in `Host` and, from a browser page,
//! come from its own page (`Origin`; [`crate::doors`]), and every request but
//! the favicon's must carry the token ([`crate::token`]); without them the
//! answer is `403 Forbidden` and nothing else runs. The routes:
//! - `GET /`, `/app.js`, `/inspector.js`, `/app.css`: the page, built into the binary; it
//!   fetches nothing else, so no file of the scene's folder is served (the
//!   renderer reads the scene's meshes and textures; the page needs none);
//! - `GET /favicon.ico`, which browsers ask for without the token: `204 No Content`;
//! - `GET /ws`: the WebSocket. The server sends `state` messages (JSON text)
//!   when the view changes, and each frame as a `frame` message (JSON text)
//!   followed at once by its pixels (binary: `width * height * 3` little-endian
//!   `f32`, linear radiance, rows from the top). The page sends `camera`,
//!   `reset`, `settings`, `explain`, `save`, `save_camera`, `frame`, `play` and `pause` messages
//!   ([`crate::messages`]), at most [`MAX_MESSAGE`] bytes each: a longer one
//!   closes the WebSocket with code 1009 (message too big).

use std::sync::Arc;

use axum::extract::ws::{close_code, CloseFrame, Message, WebSocket, WebSocketUpgrade};
use axum::extract::{Request, State};
use axum::http::{header, HeaderValue, StatusCode};
use axum::middleware::{self, Next};
use axum::response::{IntoResponse, Response};
use axum::routing::get;
use axum::Router;
use tokio::sync::mpsc;

use crate::doors::Doors;
use crate::explainer::Explainer;
use crate::renderer::Frame;
use crate::state::App;

/// Longest message a page may send (a camera or a setting is some 200 bytes).
pub const MAX_MESSAGE: usize = 64 * 1024;

/// How long a session that closed a WebSocket for a too long message waits
/// before dropping the connection (see `page_session`).
const CLOSE_LINGER: std::time::Duration = std::time::Duration::from_millis(500);

const INDEX_HTML: &str = include_str!("page/index.html");
const APP_JS: &str = include_str!("page/app.js");
const INSPECTOR_JS: &str = include_str!("page/inspector.js");
const APP_CSS: &str = include_str!("page/app.css");

/// The routes, behind the token check, all behind the doors of `doors`.
pub fn router(app: Arc<App>, doors: Doors) -> Router {
    let doors = Arc::new(doors);
    Router::new()
        .route("/", get(index))
        .route("/app.js", get(|| async { text(APP_JS, "text/javascript; charset=utf-8") }))
        .route("/inspector.js", get(|| async { text(INSPECTOR_JS, "text/javascript; charset=utf-8") }))
        .route("/app.css", get(|| async { text(APP_CSS, "text/css; charset=utf-8") }))
        .route("/ws", get(websocket))
        .fallback(|| async { (StatusCode::NOT_FOUND, "not found: the viewer serves its page only\n") })
        .layer(middleware::from_fn_with_state(app.clone(), require_token))
        // Browsers ask for it unprompted, without the token: an empty answer
        // (not a 403 in the console); added after the token layer, which
        // wraps only the routes above.
        .route("/favicon.ico", get(|| async { StatusCode::NO_CONTENT }))
        .layer(middleware::from_fn(move |request: Request, next: Next| {
            let doors = doors.clone();
            async move { check_doors(&doors, request, next).await }
        }))
        .with_state(app)
}

async fn check_doors(doors: &Doors, request: Request, next: Next) -> Response {
    let verdict = {
        let header = |name| request.headers().get(name).map(|v| v.to_str().unwrap_or("(not text)"));
        doors.check(header(header::HOST), header(header::ORIGIN))
    };
    match verdict {
        Ok(()) => next.run(request).await,
        Err(why) => (StatusCode::FORBIDDEN, why).into_response(),
    }
}

fn text(body: &'static str, kind: &'static str) -> Response {
    ([(header::CONTENT_TYPE, kind), (header::CACHE_CONTROL, "no-store")], body).into_response()
}

/// The token from `?token=` or the `X-Lamplight-Token` header.
fn given_token(request: &Request) -> Option<String> {
    let from_query = request.uri().query().into_iter().flat_map(|q| q.split('&')).find_map(|pair| pair.strip_prefix("token="));
    let from_header = request.headers().get("x-lamplight-token").and_then(|v| v.to_str().ok());
    from_query.or(from_header).map(str::to_string)
}

async fn require_token(State(app): State<Arc<App>>, request: Request, next: Next) -> Response {
    match given_token(&request) {
        Some(t) if crate::token::matches(&app.token, &t) => next.run(request).await,
        _ => (StatusCode::FORBIDDEN, "forbidden: this request lacks the viewer's token; open the URL that `lamplight view` printed\n")
            .into_response(),
    }
}

async fn index(State(app): State<Arc<App>>) -> Response {
    let page = INDEX_HTML.replace("{{TOKEN}}", &app.token);
    let mut response = ([(header::CACHE_CONTROL, "no-store")], page).into_response();
    response.headers_mut().insert(header::CONTENT_TYPE, HeaderValue::from_static("text/html; charset=utf-8"));
    // The page runs its own script only and talks only to this server.
    response.headers_mut().insert(
        header::CONTENT_SECURITY_POLICY,
        HeaderValue::from_static("default-src 'self'; img-src 'self' data: blob:; connect-src 'self'"),
    );
    response
}

async fn websocket(State(app): State<Arc<App>>, upgrade: WebSocketUpgrade) -> Response {
    upgrade.max_message_size(MAX_MESSAGE).max_frame_size(MAX_MESSAGE).on_upgrade(move |socket| page_session(app, socket))
}

/// The `frame` message and the pixels of `frame`.
fn frame_messages(frame: &Frame) -> (String, Vec<u8>) {
    let o = &frame.wanted.job.options;
    let info = serde_json::json!({
        "type": "frame",
        "generation": frame.wanted.generation,
        "width": frame.image.width,
        "height": frame.image.height,
        "full_width": o.width,
        "full_height": o.height,
        "spp": frame.spp,
        "target_spp": o.spp,
        "adaptive": o.adaptive.is_some(),
        "integrator": o.integrator.name,
        "last": frame.last,
        // The frame of an animated scene this image is of (`null`: a static scene).
        "frame": frame.wanted.loaded.frame,
        // Play's frames are previews only (`last` stays false).
        "preview": frame.wanted.preview,
        "samples_per_second": frame.samples_per_second,
        "latency_ms": frame.latency.as_secs_f64() * 1e3,
        // What denoising added to this frame (absent when it is not denoised).
        "denoise_ms": frame.denoise_time.map(|t| t.as_secs_f64() * 1e3),
    });
    let mut bytes = Vec::with_capacity(frame.image.pixels.len() * 12);
    for p in &frame.image.pixels {
        for c in p {
            bytes.extend_from_slice(&c.to_le_bytes());
        }
    }
    (info.to_string(), bytes)
}

/// One page: sends it the latest state and frame whenever they change (a slow
/// page skips frames rather than queueing them) and answers its messages.
async fn page_session(app: Arc<App>, mut socket: WebSocket) {
    let mut frames = app.frames.subscribe();
    let mut status = app.status.subscribe();
    frames.mark_changed();
    status.mark_changed();
    // Answers of slow requests (explain, save), at most a few waiting.
    let (answers, mut answered) = mpsc::channel::<String>(4);
    let explainer = Explainer::default();
    loop {
        tokio::select! {
            message = socket.recv() => match message {
                Some(Ok(Message::Text(text))) => {
                    if let Some(reply) = crate::messages::handle(&app, text.as_str(), &answers, &explainer) {
                        if socket.send(Message::Text(reply.into())).await.is_err() {
                            break;
                        }
                    }
                }
                Some(Ok(Message::Binary(_))) => {
                    let reply = crate::messages::error_reply("the page sends JSON text messages only");
                    if socket.send(Message::Text(reply.into())).await.is_err() {
                        break;
                    }
                }
                Some(Ok(_)) => {}
                Some(Err(e)) => {
                    // Too long a message (tungstenite's capacity error): say so
                    // with 1009 rather than drop the connection unexplained.
                    if e.to_string().contains("Space limit exceeded") {
                        let reason = format!("a message is at most {MAX_MESSAGE} bytes");
                        let close = CloseFrame { code: close_code::SIZE, reason: reason.into() };
                        if socket.send(Message::Close(Some(close))).await.is_ok() {
                            // The rest of the long message is still unread here, and
                            // closing a TCP socket with unread data resets the
                            // connection, which can destroy the close frame before
                            // the page reads it. Give the page time to read it.
                            tokio::time::sleep(CLOSE_LINGER).await;
                        }
                    }
                    break;
                }
                None => break,
            },
            Ok(()) = status.changed() => {
                let message = status.borrow_and_update().to_string();
                if socket.send(Message::Text(message.into())).await.is_err() {
                    break;
                }
            }
            Ok(()) = frames.changed() => {
                let frame = frames.borrow_and_update().clone();
                if let Some(frame) = frame {
                    let (info, pixels) = frame_messages(&frame);
                    if socket.send(Message::Text(info.into())).await.is_err()
                        || socket.send(Message::Binary(pixels.into())).await.is_err()
                    {
                        break;
                    }
                }
            }
            Some(reply) = answered.recv() => {
                if socket.send(Message::Text(reply.into())).await.is_err() {
                    break;
                }
            }
        }
    }
    explainer.close();
}
